//! A minimal netCDF classic (CDF-1) writer, for tests that author small synthetic weather
//! grids (format: NetCDF Users Guide, "The NetCDF Classic Format Specification"): dimensions
//! without a record dimension, double variables with text attributes.

/// A variable of a synthetic file: name, dimension indices, text attributes, f64 data.
pub struct Var<'a> {
    /// Variable name.
    pub name: &'a str,
    /// Indices of its dimensions.
    pub dims: Vec<usize>,
    /// Text attributes.
    pub attrs: Vec<(&'a str, &'a str)>,
    /// Values, row-major.
    pub data: Vec<f64>,
}

fn put_u32(out: &mut Vec<u8>, v: usize) {
    out.extend_from_slice(&u32::try_from(v).expect("small").to_be_bytes());
}

fn put_name(out: &mut Vec<u8>, name: &str) {
    put_u32(out, name.len());
    out.extend_from_slice(name.as_bytes());
    while out.len() % 4 != 0 {
        out.push(0);
    }
}

/// Serialises dimensions and double variables as a CDF-1 file (no record dimension).
pub fn classic_nc(dims: &[(&str, usize)], vars: &[Var<'_>]) -> Vec<u8> {
    classic_nc_numeric(dims, vars, &[])
}

/// [`classic_nc`] with numeric (double) attributes as well: `(variable, attribute, values)`,
/// written after the variable's text attributes.
pub fn classic_nc_numeric(
    dims: &[(&str, usize)],
    vars: &[Var<'_>],
    numbers: &[(&str, &str, &[f64])],
) -> Vec<u8> {
    const NC_DIMENSION: usize = 0x0A;
    const NC_VARIABLE: usize = 0x0B;
    const NC_ATTRIBUTE: usize = 0x0C;
    const NC_CHAR: usize = 2;
    const NC_DOUBLE: usize = 6;
    let header = |begins: &[usize]| {
        let mut h = b"CDF\x01".to_vec();
        put_u32(&mut h, 0); // numrecs
        put_u32(&mut h, NC_DIMENSION);
        put_u32(&mut h, dims.len());
        for (name, size) in dims {
            put_name(&mut h, name);
            put_u32(&mut h, *size);
        }
        put_u32(&mut h, 0); // no global attributes
        put_u32(&mut h, 0);
        put_u32(&mut h, NC_VARIABLE);
        put_u32(&mut h, vars.len());
        for (v, begin) in vars.iter().zip(begins) {
            put_name(&mut h, v.name);
            put_u32(&mut h, v.dims.len());
            for d in &v.dims {
                put_u32(&mut h, *d);
            }
            let own: Vec<&(&str, &str, &[f64])> = numbers
                .iter()
                .filter(|(var, _, _)| *var == v.name)
                .collect();
            if v.attrs.is_empty() && own.is_empty() {
                put_u32(&mut h, 0);
                put_u32(&mut h, 0);
            } else {
                put_u32(&mut h, NC_ATTRIBUTE);
                put_u32(&mut h, v.attrs.len() + own.len());
                for (name, value) in &v.attrs {
                    put_name(&mut h, name);
                    put_u32(&mut h, NC_CHAR);
                    put_name(&mut h, value);
                }
                for (_, name, values) in own {
                    put_name(&mut h, name);
                    put_u32(&mut h, NC_DOUBLE);
                    put_u32(&mut h, values.len());
                    for x in *values {
                        h.extend_from_slice(&x.to_be_bytes());
                    }
                }
            }
            put_u32(&mut h, NC_DOUBLE);
            put_u32(&mut h, v.data.len() * 8);
            put_u32(&mut h, *begin);
        }
        h
    };
    let size = header(&vec![0; vars.len()]).len();
    let mut begins = Vec::new();
    let mut offset = size;
    for v in vars {
        begins.push(offset);
        offset += v.data.len() * 8;
    }
    let mut out = header(&begins);
    for v in vars {
        for x in &v.data {
            out.extend_from_slice(&x.to_be_bytes());
        }
    }
    out
}
