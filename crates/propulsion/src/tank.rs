//! Tanks and their fluids over time (docs/physics.md §15.2; RocketPy `MassFlowRateBasedTank`,
//! `UllageBasedTank`, `LevelBasedTank`, `MassBasedTank`, rocketpy/motors/tank.py).
//!
//! Every tank quantity is a table on the grid `t_k = linspace(t_s, t_e, N)` of the tank's
//! `flux_time` (`N = discretize`, RocketPy's default 100). The input curves are first
//! functions of time — linear between their points; outside them a flow rate is 0 and every
//! other curve holds its end value — and are then resampled at the grid nodes (linear, constant
//! outside), as RocketPy's `set_discrete` does.
//!
//! Without resampling (`discretize = None`, RocketPy's `discretize=None`) the grid is the
//! points of the curve that defines the contents — the ullage, the liquid height, or the
//! liquid and gas masses, which RocketPy's `Function` arithmetic then requires on the same
//! times — and its values are taken as given; RocketPy 1.13 builds no mass-flow-rate tank so
//! (its mass integral needs a number of points), nor one from a constant curve (its densities
//! are resampled on the curve's points). The densities are `ρ(T, p)` when the temperature and
//! pressure are constant, else `ρ` tabulated linearly on their points and sampled at the
//! nodes; RocketPy's inertia is then a spline in the first case, linear in the second (linear
//! whenever the tank is resampled). Per kind, at the nodes:
//!
//! - mass flow rate: `m_l(t_k) = m_l0 + ∫_{t_s}^{t_k} (ṁ_l,in − ṁ_l,out)` exactly (the net flow
//!   is linear between the nodes), likewise the gas; masses are splines;
//! - ullage: `V_g` = the ullage, `V_l = V_total − V_g`; level: `V_l = V(h_l)`,
//!   `V_g = V_total − V_l`; mass: `V = m/ρ`; masses `m = Vρ` (interpolated as below);
//! - liquid height `h_l = h(V_l)` and gas height `h_g = h(V_l + V_g)` (the geometry's inverse
//!   volume; `h_g = top` for ullage and level tanks).
//!
//! Then the centroids and inertia follow from the geometry's moment tables
//! ([`crate::TankGeometry`]):
//!
//! ```text
//! c_l = M(h_l)/V_l,  c_g = [M(h_g) − M(h_l)]/V_g,  c = (c_l m_l + c_g m_g)/(m_l + m_g)
//! I   = ρ_l [I_x(h_l) − V_l c_l² + V_l (c_l − c)²] + ρ_g [I_x(h_g) − I_x(h_l) − V_g c_g² + V_g (c_g − c)²]
//! ```
//!
//! (`c_l = bottom` where `V_l < 1e-4 V_total`, `c_g = h_l` where `V_g < 1e-4 V_total`,
//! `c = bottom` where `m < 1e-3 V_total ρ_g`); `c` is a spline, `I` linear (see above), both
//! constant outside the grid. The masses are splines for a mass-flow tank, linear for ullage
//! and mass tanks; a level tank's liquid volume is the geometry's volume spline (zero outside
//! the tank) composed with the level, so its liquid and total masses are splines that are
//! **zero outside the grid** (RocketPy 1.13), its gas mass a spline held constant, and its
//! liquid height the input, linear. A tank given by its contents has the net mass flow of the
//! derivative of its mass table at the nodes, interpolated and extrapolated as that table. The
//! fluids have no axial inertia. RocketPy's consistency checks are errors: a negative liquid mass,
//! a gas mass below −1e-6 kg, a fluid volume outside `[−1e-6, V_total + 1e-6]` m³ or a height more
//! than 1e-4 m outside the tank.

use karman_math::{Extrapolation, Interpolation, PhysicalConstants, Table1, linspace};

use crate::propellant::{finite, non_negative};
use crate::{Fluid, PropulsionError, TankGeometry};

/// RocketPy's default number of grid nodes of a tank.
pub const DEFAULT_DISCRETIZE: usize = 100;
/// Default tank temperature, K (RocketPy `Tank(temperature=273.15)`).
pub const DEFAULT_TEMPERATURE: f64 = 273.15;
/// Default tank pressure, Pa (RocketPy `Tank(pressure=101325)`).
pub const DEFAULT_PRESSURE: f64 = 101_325.0;

/// Fraction of the tank volume below which a fluid column has no centroid of its own.
const EMPTY_VOLUME_FRACTION: f64 = 1e-4;
/// Fraction of the tank's volume of gas below which the tank's centroid is its bottom.
const EMPTY_MASS_FRACTION: f64 = 1e-3;
/// Rounding allowance of the liquid-mass check, relative to the largest liquid mass: a tank
/// that drains exactly at its last node lands within rounding of 0 on either side.
const MASS_ROUNDING: f64 = 1e-12;

/// A tank input curve of time: a constant or points `(t, value)`, linear between them.
#[derive(Debug, Clone, PartialEq)]
pub enum TankCurve {
    /// The same value at all times.
    Constant(f64),
    /// Points `(t s, value)`, strictly increasing in time.
    Points {
        /// Times, s.
        times: Vec<f64>,
        /// Values.
        values: Vec<f64>,
    },
}

impl TankCurve {
    /// The curve's own points `(times, values)`; `None` for a constant.
    fn points(&self) -> Option<(&[f64], &[f64])> {
        match self {
            TankCurve::Constant(_) => None,
            TankCurve::Points { times, values } => Some((times, values)),
        }
    }

    /// The curve's value at each node of `grid`: on its own points (a tank without
    /// resampling) its values as given, elsewhere [`TankCurve::sample`].
    fn on(
        &self,
        grid: &Grid,
        is_flow: bool,
        what: &'static str,
    ) -> Result<Vec<f64>, PropulsionError> {
        match self {
            TankCurve::Points { values, .. } if grid.own => {
                for &v in values {
                    finite(what, v)?;
                }
                Ok(values.clone())
            }
            _ => self.sample(&grid.times, is_flow, what),
        }
    }

    /// The curve's value at each of `times`: a flow rate is 0 outside its points, any other
    /// curve holds its end values.
    fn sample(
        &self,
        times: &[f64],
        is_flow: bool,
        what: &'static str,
    ) -> Result<Vec<f64>, PropulsionError> {
        match self {
            TankCurve::Constant(v) => {
                finite(what, *v)?;
                Ok(vec![*v; times.len()])
            }
            TankCurve::Points { times: ts, values } => {
                let extrapolation = if is_flow {
                    Extrapolation::Zero
                } else {
                    Extrapolation::Constant
                };
                let table = Table1::new(
                    ts.clone(),
                    values.clone(),
                    Interpolation::Linear,
                    extrapolation,
                )
                .map_err(PropulsionError::table(what))?;
                Ok(times.iter().map(|&t| table.eval(t)).collect())
            }
        }
    }
}

/// What a tank is given over time (RocketPy's four tank classes).
#[derive(Debug, Clone, PartialEq)]
pub enum TankKind {
    /// `MassFlowRateBasedTank`: initial masses and the four flows (kg/s).
    MassFlowRate {
        /// Initial liquid mass, kg.
        initial_liquid_mass: f64,
        /// Initial gas mass, kg.
        initial_gas_mass: f64,
        /// Liquid flowing in, kg/s.
        liquid_in: TankCurve,
        /// Liquid flowing out, kg/s.
        liquid_out: TankCurve,
        /// Gas flowing in, kg/s.
        gas_in: TankCurve,
        /// Gas flowing out, kg/s.
        gas_out: TankCurve,
    },
    /// `UllageBasedTank`: the gas volume, m³.
    Ullage(TankCurve),
    /// `LevelBasedTank`: the liquid surface height in the tank frame, m.
    Level(TankCurve),
    /// `MassBasedTank`: liquid and gas masses, kg.
    Mass {
        /// Liquid mass, kg.
        liquid: TankCurve,
        /// Gas mass, kg.
        gas: TankCurve,
    },
}

impl TankKind {
    /// RocketPy's class name.
    #[must_use]
    pub fn class_name(&self) -> &'static str {
        match self {
            TankKind::MassFlowRate { .. } => "MassFlowRateBasedTank",
            TankKind::Ullage(_) => "UllageBasedTank",
            TankKind::Level(_) => "LevelBasedTank",
            TankKind::Mass { .. } => "MassBasedTank",
        }
    }
}

/// Everything a tank is built from.
#[derive(Debug, Clone, PartialEq)]
pub struct TankSpec {
    /// Name shown in reports and errors.
    pub name: String,
    /// The tank's kind and its curves.
    pub kind: TankKind,
    /// Geometry.
    pub geometry: TankGeometry,
    /// `(t_s, t_e)`, s.
    pub flux_time: (f64, f64),
    /// The liquid.
    pub liquid: Fluid,
    /// The gas.
    pub gas: Fluid,
    /// Number of grid nodes `N` (at least 2) on `flux_time`, or `None` (RocketPy's
    /// `discretize=None`): the tank's curves keep their own points, which must be tables — the
    /// ullage, the liquid height, or the liquid and gas masses on the same times; RocketPy
    /// 1.13 builds no mass-flow-rate tank so.
    pub discretize: Option<usize>,
    /// Temperature, K (feeds tabulated densities).
    pub temperature: TankCurve,
    /// Pressure, Pa (feeds tabulated densities).
    pub pressure: TankCurve,
}

/// A tank with its tables of time, built once.
#[derive(Debug, Clone, PartialEq)]
pub struct Tank {
    spec: TankSpec,
    liquid_mass: Table1,
    gas_mass: Table1,
    mass: Table1,
    net_mass_flow: Table1,
    liquid_height: Table1,
    gas_height: Table1,
    center_of_mass: Table1,
    inertia: Table1,
}

/// The time nodes of a tank's tables.
struct Grid {
    times: Vec<f64>,
    /// Whether they are the points of the tank's own curves (no resampling).
    own: bool,
}

impl Grid {
    /// `linspace(flux_time, N)`, or the points of the curve(s) that define the kind's contents
    /// when `discretize` is `None`: RocketPy 1.13 then resamples nothing, and builds the tank
    /// only from tables (its densities are resampled on those points, which a constant has
    /// not), the two masses of a mass-based tank on the same times.
    fn of(spec: &TankSpec) -> Result<Grid, PropulsionError> {
        let n = match spec.discretize {
            Some(n) => n,
            None => return Self::own(&spec.kind),
        };
        if n < 2 {
            return Err(PropulsionError::InvalidParameter {
                name: "discretize",
                value: n as f64,
                reason: "needs at least 2 grid nodes",
            });
        }
        let (ts, te) = spec.flux_time;
        Ok(Grid {
            times: linspace(ts, te, n),
            own: false,
        })
    }

    fn own(kind: &TankKind) -> Result<Grid, PropulsionError> {
        let unsupported = |name, reason| PropulsionError::InvalidParameter {
            name,
            value: f64::NAN,
            reason,
        };
        let table = |curve: &TankCurve, name| {
            curve.points().map(|(t, _)| t.to_vec()).ok_or(unsupported(
                name,
                "must be a table of time without resampling (discretize = false)",
            ))
        };
        let times = match kind {
            TankKind::MassFlowRate { .. } => {
                return Err(unsupported(
                    "discretize",
                    "RocketPy 1.13 builds no mass-flow-rate tank without resampling",
                ));
            }
            TankKind::Ullage(ullage) => table(ullage, "ullage")?,
            TankKind::Level(level) => table(level, "liquid_height")?,
            TankKind::Mass { liquid, gas } => {
                let times = table(liquid, "liquid_mass")?;
                if table(gas, "gas_mass")? != times {
                    return Err(unsupported(
                        "gas_mass",
                        "must be given at the times of liquid_mass without resampling \
                         (discretize = false)",
                    ));
                }
                times
            }
        };
        Ok(Grid { times, own: true })
    }
}

/// Densities of the liquid and the gas at the grid nodes, and the interpolation RocketPy
/// gives the tank's inertia through them.
struct Densities {
    liquid: Vec<f64>,
    gas: Vec<f64>,
    inertia_interpolation: Interpolation,
}

impl Densities {
    /// `ρ(T(t), p(t))` at the nodes. Resampled (`discretize = N`), the temperature and
    /// pressure are taken at the nodes; the inertia is linear. Without resampling, RocketPy
    /// tabulates `ρ` linearly on the points of the temperature and pressure tables (both
    /// joined; `ρ(T, p)` itself if both are constant) and samples that at the nodes; its
    /// inertia is then linear, or a spline when both are constant.
    fn at(spec: &TankSpec, grid: &Grid) -> Result<Densities, PropulsionError> {
        spec.liquid.validate("liquid density")?;
        spec.gas.validate("gas density")?;
        let (temperature, pressure) = (&spec.temperature, &spec.pressure);
        let source: Vec<f64> = match (grid.own, temperature.points(), pressure.points()) {
            (false, _, _) => grid.times.clone(),
            (true, None, None) => Vec::new(),
            (true, a, b) => {
                let mut times: Vec<f64> = a
                    .into_iter()
                    .chain(b)
                    .flat_map(|(t, _)| t)
                    .copied()
                    .collect();
                times.sort_by(f64::total_cmp);
                times.dedup();
                times
            }
        };
        let constant_state = grid.own && source.is_empty();
        let state = |times: &[f64]| -> Result<(Vec<f64>, Vec<f64>), PropulsionError> {
            Ok((
                temperature.sample(times, false, "tank temperature")?,
                pressure.sample(times, false, "tank pressure")?,
            ))
        };
        let (t, p) = state(if constant_state { &grid.times } else { &source })?;
        let mut out = Vec::with_capacity(2);
        for (fluid, name) in [(&spec.liquid, "liquid density"), (&spec.gas, "gas density")] {
            let rho: Vec<f64> = t
                .iter()
                .zip(&p)
                .map(|(&t, &p)| fluid.density_at(t, p))
                .collect();
            if let Some(&bad) = rho.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
                return Err(PropulsionError::InvalidParameter {
                    name,
                    value: bad,
                    reason: "must be a positive number at the tank's temperature and pressure",
                });
            }
            out.push(if grid.own && !constant_state {
                let table = Table1::new(
                    source.clone(),
                    rho,
                    Interpolation::Linear,
                    Extrapolation::Constant,
                )
                .map_err(PropulsionError::table(name))?;
                grid.times.iter().map(|&t| table.eval(t)).collect()
            } else {
                rho
            });
        }
        let gas = out.pop().unwrap_or_default();
        let liquid = out.pop().unwrap_or_default();
        Ok(Densities {
            liquid,
            gas,
            inertia_interpolation: if constant_state {
                Interpolation::Spline
            } else {
                Interpolation::Linear
            },
        })
    }
}

/// Node values of one tank, before tabulation.
struct Nodes {
    liquid_mass: Vec<f64>,
    gas_mass: Vec<f64>,
    liquid_volume: Vec<f64>,
    gas_volume: Vec<f64>,
    liquid_height: Vec<f64>,
    gas_height: Vec<f64>,
}

/// How RocketPy interpolates and extrapolates a kind's tables of time, as its `Function`
/// arithmetic hands them on.
struct KindTables {
    /// Liquid, gas and total mass: interpolation, and the extrapolations of the liquid, the
    /// gas and the total.
    mass: (Interpolation, [Extrapolation; 3]),
    /// The liquid height (the input of a level tank, else through the inverse volume).
    liquid_height: (Interpolation, Extrapolation),
    /// The net mass flow at the nodes and its extrapolation (the flows of a mass-flow tank,
    /// else the derivative of its mass table, extrapolated as the mass).
    net_mass_flow: (Vec<f64>, Interpolation, Extrapolation),
}

impl Tank {
    /// Builds the tank's tables (docs/physics.md §15.2), inputs in the unit system of `constants`
    /// (which holds the slacks of RocketPy's checks).
    ///
    /// # Errors
    /// [`PropulsionError::InvalidParameter`] for a bad flux time, grid size or initial mass, or
    /// a tank without resampling whose curves are not tables on one set of times;
    /// [`PropulsionError::TankContents`] when the fluids over- or underfill the tank (naming
    /// the tank, the quantity, the time and the limit); [`PropulsionError::Table`] for curves
    /// that do not form tables.
    pub fn new(spec: TankSpec, constants: &PhysicalConstants) -> Result<Tank, PropulsionError> {
        let (ts, te) = spec.flux_time;
        non_negative("flux_time start", ts)?;
        if !(te.is_finite() && te > ts) {
            return Err(PropulsionError::InvalidParameter {
                name: "flux_time",
                value: te,
                reason: "must end after it starts",
            });
        }
        let grid = Grid::of(&spec)?;
        let densities = Densities::at(&spec, &grid)?;
        let (rho_l, rho_g) = (&densities.liquid, &densities.gas);
        let times = &grid.times;
        let g = &spec.geometry;
        let total = g.total_volume();
        let (nodes, kind_tables) = Self::nodes(&spec, &grid, rho_l, rho_g, total)?;
        check(&spec, times, &nodes, total, constants)?;
        let n = times.len();
        let bottom = g.bottom();
        let max = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let liquid_moment = g.volume_moment(bottom, max(&nodes.liquid_height))?;
        let liquid_inertia = g.inertia_volume(bottom, max(&nodes.liquid_height))?;
        let fluid_moment = g.volume_moment(bottom, max(&nodes.gas_height))?;
        let fluid_inertia = g.inertia_volume(bottom, max(&nodes.gas_height))?;
        let mut centers = Vec::with_capacity(n);
        let mut inertias = Vec::with_capacity(n);
        for k in 0..n {
            let (ml, mg) = (nodes.liquid_mass[k], nodes.gas_mass[k]);
            let (vl, vg) = (nodes.liquid_volume[k], nodes.gas_volume[k]);
            let (hl, hg) = (nodes.liquid_height[k], nodes.gas_height[k]);
            let cl = if vl < EMPTY_VOLUME_FRACTION * total {
                bottom
            } else {
                liquid_moment.eval(hl) / vl
            };
            let cg = if vg < EMPTY_VOLUME_FRACTION * total {
                hl
            } else {
                (fluid_moment.eval(hg) - fluid_moment.eval(hl)) / vg
            };
            let m = ml + mg;
            let c = if m < EMPTY_MASS_FRACTION * total * rho_g[k] {
                bottom
            } else {
                (cl * ml + cg * mg) / m
            };
            let il = rho_l[k] * (liquid_inertia.eval(hl) - vl * cl * cl + vl * (cl - c).powi(2));
            let ig = rho_g[k]
                * (fluid_inertia.eval(hg) - fluid_inertia.eval(hl) - vg * cg * cg
                    + vg * (cg - c).powi(2));
            centers.push(c);
            inertias.push(il + ig);
        }
        let hold = Extrapolation::Constant;
        let table = |ys: Vec<f64>, interpolation, extrapolation, what| {
            Table1::new(times.clone(), ys, interpolation, extrapolation)
                .map_err(PropulsionError::table(what))
        };
        let masses: Vec<f64> = (0..n)
            .map(|k| nodes.liquid_mass[k] + nodes.gas_mass[k])
            .collect();
        let (mass_interpolation, [liquid_extrapolation, gas_extrapolation, mass_extrapolation]) =
            kind_tables.mass;
        let (flow, flow_interpolation, flow_extrapolation) = kind_tables.net_mass_flow;
        Ok(Tank {
            liquid_mass: table(
                nodes.liquid_mass,
                mass_interpolation,
                liquid_extrapolation,
                "tank liquid mass",
            )?,
            gas_mass: table(
                nodes.gas_mass,
                mass_interpolation,
                gas_extrapolation,
                "tank gas mass",
            )?,
            mass: table(masses, mass_interpolation, mass_extrapolation, "tank mass")?,
            net_mass_flow: table(
                flow,
                flow_interpolation,
                flow_extrapolation,
                "tank net mass flow",
            )?,
            liquid_height: table(
                nodes.liquid_height,
                kind_tables.liquid_height.0,
                kind_tables.liquid_height.1,
                "tank liquid height",
            )?,
            gas_height: table(
                nodes.gas_height,
                Interpolation::Spline,
                Extrapolation::Natural,
                "tank gas height",
            )?,
            center_of_mass: table(centers, Interpolation::Spline, hold, "tank centre of mass")?,
            inertia: table(
                inertias,
                densities.inertia_interpolation,
                hold,
                "tank inertia",
            )?,
            spec,
        })
    }

    /// Node values of the kind and the interpolations of its tables.
    fn nodes(
        spec: &TankSpec,
        grid: &Grid,
        rho_l: &[f64],
        rho_g: &[f64],
        total: f64,
    ) -> Result<(Nodes, KindTables), PropulsionError> {
        let g = &spec.geometry;
        let times = &grid.times;
        let n = times.len();
        let top = vec![g.top(); n];
        let heights_of =
            |v: &[f64]| -> Vec<f64> { v.iter().map(|&v| g.height_of_volume(v)).collect() };
        let by_node = |a: &[f64], b: &[f64], f: &dyn Fn(f64, f64) -> f64| -> Vec<f64> {
            a.iter().zip(b).map(|(&x, &y)| f(x, y)).collect()
        };
        let hold = Extrapolation::Constant;
        let through_volume = (Interpolation::Spline, Extrapolation::Natural);
        let (nodes, mass) = match &spec.kind {
            TankKind::MassFlowRate {
                initial_liquid_mass,
                initial_gas_mass,
                liquid_in,
                liquid_out,
                gas_in,
                gas_out,
            } => {
                non_negative("initial_liquid_mass", *initial_liquid_mass)?;
                non_negative("initial_gas_mass", *initial_gas_mass)?;
                let net = |flow_in: &TankCurve, flow_out: &TankCurve, what| {
                    let i = flow_in.on(grid, true, what)?;
                    let o = flow_out.on(grid, true, what)?;
                    Table1::new(
                        times.clone(),
                        by_node(&i, &o, &|a, b| a - b),
                        Interpolation::Linear,
                        Extrapolation::Zero,
                    )
                    .map_err(PropulsionError::table(what))
                };
                let liquid_net = net(liquid_in, liquid_out, "liquid mass flow rate")?;
                let gas_net = net(gas_in, gas_out, "gas mass flow rate")?;
                let t0 = times[0];
                let liquid_mass: Vec<f64> = times
                    .iter()
                    .map(|&t| initial_liquid_mass + liquid_net.integral(t0, t))
                    .collect();
                let gas_mass: Vec<f64> = times
                    .iter()
                    .map(|&t| initial_gas_mass + gas_net.integral(t0, t))
                    .collect();
                let net_flow = by_node(liquid_net.ys(), gas_net.ys(), &|a, b| a + b);
                let liquid_volume = by_node(&liquid_mass, rho_l, &|m, r| m / r);
                let gas_volume = by_node(&gas_mass, rho_g, &|m, r| m / r);
                let fluid_volume = by_node(&liquid_volume, &gas_volume, &|a, b| a + b);
                let nodes = Nodes {
                    liquid_height: heights_of(&liquid_volume),
                    gas_height: heights_of(&fluid_volume),
                    liquid_mass,
                    gas_mass,
                    liquid_volume,
                    gas_volume,
                };
                let tables = KindTables {
                    mass: (Interpolation::Spline, [hold; 3]),
                    liquid_height: through_volume,
                    net_mass_flow: (net_flow, Interpolation::Linear, Extrapolation::Zero),
                };
                return Ok((nodes, tables));
            }
            TankKind::Ullage(ullage) => {
                let gas_volume = ullage.on(grid, false, "ullage")?;
                let liquid_volume: Vec<f64> = gas_volume.iter().map(|v| total - v).collect();
                let nodes = Nodes {
                    liquid_mass: by_node(&liquid_volume, rho_l, &|v, r| v * r),
                    gas_mass: by_node(&gas_volume, rho_g, &|v, r| v * r),
                    liquid_height: heights_of(&liquid_volume),
                    gas_height: top,
                    liquid_volume,
                    gas_volume,
                };
                (nodes, (Interpolation::Linear, [hold; 3], through_volume))
            }
            TankKind::Level(level) => {
                let liquid_height = level.on(grid, false, "liquid_height")?;
                let liquid_volume: Vec<f64> = liquid_height.iter().map(|&h| g.volume(h)).collect();
                let gas_volume: Vec<f64> = liquid_volume.iter().map(|v| total - v).collect();
                let nodes = Nodes {
                    liquid_mass: by_node(&liquid_volume, rho_l, &|v, r| v * r),
                    gas_mass: by_node(&gas_volume, rho_g, &|v, r| v * r),
                    liquid_height,
                    gas_height: top,
                    liquid_volume,
                    gas_volume,
                };
                // The liquid volume is the geometry's volume spline (zero outside the tank)
                // composed with the level: RocketPy's liquid and total masses inherit its
                // spline and its zero extrapolation, the gas mass (the tank volume less the
                // liquid) a spline held constant; the level is the input, linear.
                let zero = Extrapolation::Zero;
                (
                    nodes,
                    (
                        Interpolation::Spline,
                        [zero, hold, zero],
                        (Interpolation::Linear, hold),
                    ),
                )
            }
            TankKind::Mass { liquid, gas } => {
                let liquid_mass = liquid.on(grid, false, "liquid_mass")?;
                let gas_mass = gas.on(grid, false, "gas_mass")?;
                let liquid_volume = by_node(&liquid_mass, rho_l, &|m, r| m / r);
                let gas_volume = by_node(&gas_mass, rho_g, &|m, r| m / r);
                let fluid_volume = by_node(&liquid_volume, &gas_volume, &|a, b| a + b);
                let nodes = Nodes {
                    liquid_height: heights_of(&liquid_volume),
                    gas_height: heights_of(&fluid_volume),
                    liquid_mass,
                    gas_mass,
                    liquid_volume,
                    gas_volume,
                };
                (nodes, (Interpolation::Linear, [hold; 3], through_volume))
            }
        };
        let (interpolation, extrapolations, liquid_height) = mass;
        // The net flow of a tank given by its contents: the derivative of its mass table at
        // each node (RocketPy's `derivative_function`; for a linear table the slope of the
        // interval to the left, the first node's that of the first interval), tabulated with
        // the mass table's interpolation and extrapolation.
        let mass: Vec<f64> = by_node(&nodes.liquid_mass, &nodes.gas_mass, &|a, b| a + b);
        let mass_table = Table1::new(times.clone(), mass, interpolation, extrapolations[2])
            .map_err(PropulsionError::table("tank mass"))?;
        let net_flow = times.iter().map(|&t| mass_table.derivative(t)).collect();
        let tables = KindTables {
            mass: (interpolation, extrapolations),
            liquid_height,
            net_mass_flow: (net_flow, interpolation, extrapolations[2]),
        };
        Ok((nodes, tables))
    }

    /// The inputs.
    #[must_use]
    pub fn spec(&self) -> &TankSpec {
        &self.spec
    }
    /// Name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.spec.name
    }
    /// Liquid mass `m_l(t)`, kg.
    #[must_use]
    pub fn liquid_mass(&self) -> &Table1 {
        &self.liquid_mass
    }
    /// Gas mass `m_g(t)`, kg.
    #[must_use]
    pub fn gas_mass(&self) -> &Table1 {
        &self.gas_mass
    }
    /// Fluid mass `m(t) = m_l + m_g`, kg.
    #[must_use]
    pub fn mass(&self) -> &Table1 {
        &self.mass
    }
    /// Net mass flow into the tank (negative when draining), kg/s, linear, zero outside the
    /// flux time.
    #[must_use]
    pub fn net_mass_flow(&self) -> &Table1 {
        &self.net_mass_flow
    }
    /// Liquid surface height `h_l(t)`, m, tank frame.
    #[must_use]
    pub fn liquid_height(&self) -> &Table1 {
        &self.liquid_height
    }
    /// Height of the top of the gas `h_g(t)`, m, tank frame.
    #[must_use]
    pub fn gas_height(&self) -> &Table1 {
        &self.gas_height
    }
    /// Centre of mass of the fluids `c(t)`, m, tank frame.
    #[must_use]
    pub fn center_of_mass(&self) -> &Table1 {
        &self.center_of_mass
    }
    /// Transverse inertia of the fluids about their centre of mass `I(t)`, kg·m².
    #[must_use]
    pub fn inertia(&self) -> &Table1 {
        &self.inertia
    }
}

/// RocketPy's consistency checks of a tank's contents at the grid nodes.
fn check(
    spec: &TankSpec,
    times: &[f64],
    nodes: &Nodes,
    total: f64,
    constants: &PhysicalConstants,
) -> Result<(), PropulsionError> {
    let gas_slack = constants.tank_gas_mass_slack;
    let volume_slack = constants.tank_volume_slack;
    let height_slack = constants.tank_height_slack;
    let g = &spec.geometry;
    let fail = |quantity, k: usize, value, limit, reason| PropulsionError::TankContents {
        tank: spec.name.clone(),
        quantity,
        time: times[k],
        value,
        limit,
        reason,
    };
    let scale = nodes
        .liquid_mass
        .iter()
        .fold(0.0_f64, |a, m| a.max(m.abs()));
    for k in 0..times.len() {
        let (ml, mg) = (nodes.liquid_mass[k], nodes.gas_mass[k]);
        if ml < -MASS_ROUNDING * scale {
            return Err(fail("liquid mass (kg)", k, ml, 0.0, "is negative"));
        }
        if mg < -gas_slack {
            return Err(fail("gas mass (kg)", k, mg, -gas_slack, "is below"));
        }
        let volume = nodes.liquid_volume[k] + nodes.gas_volume[k];
        for (quantity, v) in [
            ("liquid volume (m^3)", nodes.liquid_volume[k]),
            ("gas volume (m^3)", nodes.gas_volume[k]),
            ("fluid volume (m^3)", volume),
        ] {
            if v > total + volume_slack {
                return Err(fail(quantity, k, v, total, "exceeds the tank volume"));
            }
            if v < -volume_slack {
                return Err(fail(quantity, k, v, -volume_slack, "is below"));
            }
        }
        for (quantity, h) in [
            ("liquid height (m)", nodes.liquid_height[k]),
            ("gas height (m)", nodes.gas_height[k]),
        ] {
            if h > g.top() + height_slack {
                return Err(fail(quantity, k, h, g.top(), "is above the tank top"));
            }
            if h < g.bottom() - height_slack {
                return Err(fail(quantity, k, h, g.bottom(), "is below the tank bottom"));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::TankShape;

    fn cylinder() -> TankGeometry {
        TankGeometry::new(
            TankShape::Cylindrical {
                radius: 0.07,
                height: 0.32,
                spherical_caps: false,
            },
            &PhysicalConstants::SI,
        )
        .unwrap()
    }

    fn build(spec: TankSpec) -> Result<Tank, PropulsionError> {
        Tank::new(spec, &PhysicalConstants::SI)
    }

    fn spec(kind: TankKind) -> TankSpec {
        TankSpec {
            name: "ox".into(),
            kind,
            geometry: cylinder(),
            flux_time: (0.0, 5.0),
            liquid: Fluid::constant("N2O_l", 960.0),
            gas: Fluid::constant("N2O_g", 1.9277),
            discretize: Some(DEFAULT_DISCRETIZE),
            temperature: TankCurve::Constant(DEFAULT_TEMPERATURE),
            pressure: TankCurve::Constant(DEFAULT_PRESSURE),
        }
    }

    fn drained(rate: f64) -> TankKind {
        filled(4.2, 0.0, rate)
    }

    fn filled(liquid: f64, gas: f64, rate: f64) -> TankKind {
        TankKind::MassFlowRate {
            initial_liquid_mass: liquid,
            initial_gas_mass: gas,
            liquid_in: TankCurve::Constant(0.0),
            liquid_out: TankCurve::Constant(rate),
            gas_in: TankCurve::Constant(0.0),
            gas_out: TankCurve::Constant(0.0),
        }
    }

    #[test]
    fn a_tank_drained_at_a_known_rate() {
        let tank = build(spec(drained(0.84))).unwrap();
        let area = std::f64::consts::PI * 0.07 * 0.07;
        for t in [0.0, 1.0, 2.5, 4.0] {
            let m = 4.2 - 0.84 * t;
            assert!((tank.mass().eval(t) - m).abs() < 1e-12, "{t}");
            // A cylinder: the liquid column from the bottom, its centroid halfway up.
            let level = -0.16 + m / 960.0 / area;
            assert!((tank.liquid_height().eval(t) - level).abs() < 1e-9, "{t}");
            let c = (-0.16 + level) / 2.0;
            assert!((tank.center_of_mass().eval(t) - c).abs() < 1e-9, "{t}");
            // A solid cylinder of height H about its centre: m (3R² + H²)/12.
            let column = level + 0.16;
            let i = m * (3.0 * 0.07 * 0.07 + column * column) / 12.0;
            // To the accuracy of the natural splines of the moment tables, whose zero end
            // curvature misses that of the cubic I_x(h) (RocketPy's tables carry the same
            // error): about 1e-6 kg·m² here, 2e-4 of the full tank's inertia.
            assert!((tank.inertia().eval(t) - i).abs() < 2e-6, "{t}");
        }
        assert!(tank.mass().eval(5.0).abs() < 1e-12 && tank.mass().eval(9.0).abs() < 1e-12);
        assert!((tank.net_mass_flow().eval(1.0) + 0.84).abs() < 1e-12);
        assert!(tank.net_mass_flow().eval(5.5).abs() < 1e-300);
    }

    #[test]
    fn over_and_underfilled_tanks_are_errors() {
        let err = build(spec(drained(1.0))).unwrap_err();
        assert!(
            matches!(
                err,
                PropulsionError::TankContents {
                    quantity: "liquid mass (kg)",
                    ..
                }
            ),
            "{err}"
        );
        let full = filled(5.0, 0.0, 0.0);
        let err = build(spec(full)).unwrap_err();
        assert!(err.to_string().contains("exceeds the tank volume"), "{err}");
        let err = build(spec(TankKind::Level(TankCurve::Constant(0.5)))).unwrap_err();
        assert!(err.to_string().contains("above the tank top"), "{err}");
    }

    #[test]
    fn the_four_kinds_agree_on_one_state() {
        // Half a tank of liquid, the rest gas, given four ways.
        let g = cylinder();
        let half = g.total_volume() / 2.0;
        let kinds = [
            filled(half * 960.0, half * 1.9277, 0.0),
            TankKind::Ullage(TankCurve::Constant(half)),
            TankKind::Level(TankCurve::Constant(0.0)),
            TankKind::Mass {
                liquid: TankCurve::Constant(half * 960.0),
                gas: TankCurve::Constant(half * 1.9277),
            },
        ];
        let tanks: Vec<Tank> = kinds.into_iter().map(|k| build(spec(k)).unwrap()).collect();
        for tank in &tanks {
            assert!((tank.liquid_mass().eval(1.0) - half * 960.0).abs() < 1e-9);
            assert!((tank.gas_mass().eval(1.0) - half * 1.9277).abs() < 1e-9);
            assert!(tank.liquid_height().eval(1.0).abs() < 1e-9);
            let c = tank.center_of_mass().eval(1.0);
            let expected = (-0.08 * half * 960.0 + 0.08 * half * 1.9277) / (half * 961.9277);
            assert!(
                (c - expected).abs() < 1e-9,
                "{}: {c}",
                tank.spec().kind.class_name()
            );
        }
    }
}
