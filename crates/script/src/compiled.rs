//! The controllers' common subset of Rhai compiled to a tree of Rust values, evaluated with
//! Rhai's own semantics: the fast path of [`crate::Controller::call`].
//!
//! Most controllers are a few statements of floating-point arithmetic on the state, the environment
//! queries and the air-brake level, which the interpreter would evaluate with boxed values and
//! functions resolved by hash (docs/performance.md, "Controllers"). [`Compiled`] is the body of
//! `controller_function` translated once, from the AST Rhai parsed and optimised, into [`Node`]s
//! over slots, and evaluated without the interpreter.
//!
//! The subset: numbers, booleans and `()`; `let`/`const`, assignment and the arithmetic
//! op-assignments to local variables and to `air_brakes.deployment_level`; `if`/`else` (also
//! as an expression); `return` with or without a value; array literals; the arithmetic,
//! comparison and logical operators; the float math functions of Rhai's standard package;
//! `state[i]`, `state_history[-1][i]` (and a `let` holding either row) at constant indices;
//! `time`, `sampling_rate`; `global::NAME` and `motor::NAME`; the air-brake handle's
//! properties and `drag_coefficient(level, mach)`; the environment's `elevation` and queries
//! of height. A script with anything else (loops, other functions, strings, maps,
//! `observed_variables`, `sensors`, ...) is left to Rhai entirely
//! ([`compile`] says why).
//!
//! Semantics are Rhai 1.27's as its engine runs (checked arithmetic, fast operators):
//! float operators are IEEE; an integer meeting a float is converted to a float; float
//! comparisons are Rhai's relative ones (`x < y` when `(y − x)/max(|x|, |y|) > ε`, with
//! `max = 1` when `x·y = 0`); `**` of floats is `powf`. Whatever the compiled tree cannot
//! decide at run time with certainty — integer arithmetic (overflow and division rules), a
//! value of another type where a float or a boolean is needed, an index out of range — is a
//! [`Bail`]: the evaluation has no effect outside its frame (the level it writes is kept in
//! the frame until the call ends), so the call is then made again by the interpreter, which
//! gives Rhai's result or its located error. Without loops or calls of script functions
//! the evaluation is bounded by the size of the tree, so the sandbox's operation limit
//! cannot be reached on this path.

use rhai::{
    AST, ASTFlags, ASTNode, Array, BinaryExpr, Dynamic, Expr, FLOAT, FnCallExpr, INT, Stmt, Token,
};

use crate::arguments::{AirBrakesSetup, EnvironmentQuery, stored_level};
use crate::sandbox;

/// A generous bound on the operations Rhai counts for one AST node evaluated once.
const OPERATIONS_PER_NODE: u64 = 8;

/// The evaluation could not decide the call: the interpreter makes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Bail;

/// A row argument: `state` or `state_history[-1]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Row {
    State,
    Last,
}

/// A value of the compiled subset.
#[derive(Debug, Clone)]
enum Value {
    Unit,
    Bool(bool),
    Int(INT),
    Float(FLOAT),
    Row(Row),
    Array(Array),
}

/// A float function of one float of Rhai's standard math package.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Math {
    Sqrt,
    Exp,
    Ln,
    Log10,
    Sin,
    Cos,
    Tan,
    Abs,
}

impl Math {
    fn of(name: &str) -> Option<Self> {
        Some(match name {
            "sqrt" => Self::Sqrt,
            "exp" => Self::Exp,
            "ln" => Self::Ln,
            "log" => Self::Log10,
            "sin" => Self::Sin,
            "cos" => Self::Cos,
            "tan" => Self::Tan,
            "abs" => Self::Abs,
            _ => return None,
        })
    }

    fn apply(self, x: FLOAT) -> FLOAT {
        match self {
            Self::Sqrt => x.sqrt(),
            Self::Exp => x.exp(),
            Self::Ln => x.ln(),
            Self::Log10 => x.log10(),
            Self::Sin => x.sin(),
            Self::Cos => x.cos(),
            Self::Tan => x.tan(),
            Self::Abs => x.abs(),
        }
    }
}

/// An environment query of height.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Query {
    WindX,
    WindY,
    SpeedOfSound,
    Density,
    Pressure,
    Temperature,
    Viscosity,
    Gravity,
}

impl Query {
    fn of(name: &str) -> Option<Self> {
        Some(match name {
            "wind_velocity_x" => Self::WindX,
            "wind_velocity_y" => Self::WindY,
            "speed_of_sound" => Self::SpeedOfSound,
            "density" => Self::Density,
            "pressure" => Self::Pressure,
            "temperature" => Self::Temperature,
            "dynamic_viscosity" => Self::Viscosity,
            "gravity" => Self::Gravity,
            _ => return None,
        })
    }

    fn at(self, environment: &dyn EnvironmentQuery, h: FLOAT) -> FLOAT {
        match self {
            Self::WindX => environment.wind_velocity_x(h),
            Self::WindY => environment.wind_velocity_y(h),
            Self::SpeedOfSound => environment.speed_of_sound(h),
            Self::Density => environment.density(h),
            Self::Pressure => environment.pressure(h),
            Self::Temperature => environment.temperature(h),
            Self::Viscosity => environment.dynamic_viscosity(h),
            Self::Gravity => environment.gravity(h),
        }
    }
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Pow,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

impl Op {
    fn of(token: &Token) -> Option<Self> {
        Some(match token {
            Token::Plus => Self::Add,
            Token::Minus => Self::Sub,
            Token::Multiply => Self::Mul,
            Token::Divide => Self::Div,
            Token::Modulo => Self::Rem,
            Token::PowerOf => Self::Pow,
            Token::EqualsTo => Self::Eq,
            Token::NotEqualsTo => Self::Ne,
            Token::LessThan => Self::Lt,
            Token::LessThanEqualsTo => Self::Le,
            Token::GreaterThan => Self::Gt,
            Token::GreaterThanEqualsTo => Self::Ge,
            _ => return None,
        })
    }

    /// The operator on two floats, as Rhai's built-in float operators (checked build).
    fn floats(self, x: FLOAT, y: FLOAT) -> Value {
        let relative = |d: FLOAT| {
            let max = if x * y == 0.0 {
                1.0
            } else {
                x.abs().max(y.abs())
            };
            (max, d / max)
        };
        match self {
            Self::Add => Value::Float(x + y),
            Self::Sub => Value::Float(x - y),
            Self::Mul => Value::Float(x * y),
            Self::Div => Value::Float(x / y),
            Self::Rem => Value::Float(x % y),
            Self::Pow => Value::Float(x.powf(y)),
            Self::Eq => {
                let (max, r) = relative((x - y).abs());
                Value::Bool(max == 0.0 || r <= FLOAT::EPSILON)
            }
            Self::Ne => {
                let (max, r) = relative((x - y).abs());
                Value::Bool(max != 0.0 && r > FLOAT::EPSILON)
            }
            Self::Gt | Self::Ge => {
                let (max, r) = relative(x - y);
                Value::Bool(if max == 0.0 {
                    self == Self::Ge
                } else if self == Self::Gt {
                    r > FLOAT::EPSILON
                } else {
                    r > -FLOAT::EPSILON
                })
            }
            Self::Lt | Self::Le => {
                let (max, r) = relative(y - x);
                Value::Bool(if max == 0.0 {
                    self == Self::Le
                } else if self == Self::Lt {
                    r > FLOAT::EPSILON
                } else {
                    r > -FLOAT::EPSILON
                })
            }
        }
    }

    fn apply(self, x: &Value, y: &Value) -> Result<Value, Bail> {
        Ok(match (x, y) {
            (Value::Float(a), Value::Float(b)) => self.floats(*a, *b),
            #[allow(clippy::cast_precision_loss)]
            (Value::Float(a), Value::Int(b)) => self.floats(*a, *b as FLOAT),
            #[allow(clippy::cast_precision_loss)]
            (Value::Int(a), Value::Float(b)) => self.floats(*a as FLOAT, *b),
            (Value::Int(a), Value::Int(b)) => Value::Bool(match self {
                Self::Eq => a == b,
                Self::Ne => a != b,
                Self::Lt => a < b,
                Self::Le => a <= b,
                Self::Gt => a > b,
                Self::Ge => a >= b,
                // Integer arithmetic (overflow, division) is left to Rhai.
                _ => return Err(Bail),
            }),
            (Value::Bool(a), Value::Bool(b)) => Value::Bool(match self {
                Self::Eq => a == b,
                Self::Ne => a != b,
                Self::Lt => !a & b,
                Self::Le => a <= b,
                Self::Gt => a & !b,
                Self::Ge => a >= b,
                _ => return Err(Bail),
            }),
            _ => return Err(Bail),
        })
    }
}

/// An expression.
#[derive(Debug, Clone)]
enum Node {
    Constant(Value),
    Local(usize),
    /// The value of `global::`/`motor::` name `i` of [`Compiled::names`].
    Name(usize),
    Time,
    SamplingRate,
    Row(Row),
    /// `row[i]` of a row-valued expression, `i` in `-len..len`.
    Index(Box<Node>, INT),
    Binary(Op, Box<Node>, Box<Node>),
    Negate(Box<Node>),
    Not(Box<Node>),
    And(Box<[Node]>),
    Or(Box<[Node]>),
    Math(Math, Box<Node>),
    Query(Query, Box<Node>),
    Elevation,
    Level,
    Clamp,
    OverrideRocketDrag,
    ReferenceArea,
    DragCoefficient(Box<Node>, Box<Node>),
    Array(Box<[Node]>),
    Block(Block),
}

/// A statement.
#[derive(Debug, Clone)]
enum Instr {
    /// `let`/`const` and assignments to locals (op-assignments compiled to their operator).
    Set(usize, Node),
    /// `x op= e` on a local holding a float.
    Update(usize, Op, Node),
    SetLevel(Node),
    UpdateLevel(Op, Node),
    If(Node, Block, Block),
    Block(Block),
    Return(Option<Node>),
    Expr(Node),
}

/// A statement block: its value is the value of its last statement.
#[derive(Debug, Clone, Default)]
struct Block(Box<[Instr]>);

/// The control flow out of a statement.
enum Flow {
    Next(Value),
    Return(Value),
}

/// What a call reads.
pub(crate) struct Inputs<'a> {
    pub time: FLOAT,
    pub sampling_rate: FLOAT,
    pub state: &'a [FLOAT; 13],
    pub last_row: &'a [FLOAT; 14],
    pub air_brakes: &'a AirBrakesSetup,
    pub environment: &'a dyn EnvironmentQuery,
}

/// The mutable part of an evaluation: the locals and the level written so far.
struct Frame<'a, 'i> {
    inputs: &'a Inputs<'i>,
    locals: &'a mut [Value],
    names: &'a [Value],
    level: FLOAT,
}

/// `controller_function` compiled; its `global::`/`motor::` names are resolved by
/// [`Compiled::bind`].
#[derive(Debug, Clone)]
pub(crate) struct Compiled {
    body: Block,
    slots: usize,
    /// The `global::`/`motor::` names read, `(namespace, name)`.
    names: Vec<(String, String)>,
}

/// Parameters by position (RocketPy's order).
const TIME: usize = 0;
const SAMPLING_RATE: usize = 1;
const STATE: usize = 2;
const STATE_HISTORY: usize = 3;
const AIR_BRAKES: usize = 5;
const ENVIRONMENT: usize = 7;

/// The translation of one function body: the names in scope and their slots.
struct Translator<'p> {
    params: &'p [String],
    scopes: Vec<Vec<(String, usize)>>,
    slots: usize,
    names: Vec<(String, String)>,
    /// AST nodes translated.
    nodes: usize,
}

type Translated<T> = Result<T, String>;

fn unsupported<T>(what: impl Into<String>) -> Translated<T> {
    Err(what.into())
}

impl Translator<'_> {
    fn local(&self, name: &str) -> Option<usize> {
        self.scopes
            .iter()
            .rev()
            .flat_map(|scope| scope.iter().rev())
            .find(|(n, _)| n == name)
            .map(|&(_, slot)| slot)
    }

    fn parameter(&self, name: &str) -> Option<usize> {
        self.params.iter().position(|p| p == name)
    }

    fn block(&mut self, statements: &[Stmt]) -> Translated<Block> {
        self.scopes.push(Vec::new());
        let block = statements
            .iter()
            .map(|s| self.statement(s))
            .collect::<Translated<Vec<_>>>();
        self.scopes.pop();
        Ok(Block(block?.into_boxed_slice()))
    }

    fn statement(&mut self, statement: &Stmt) -> Translated<Instr> {
        self.nodes += 1;
        Ok(match statement {
            Stmt::Noop(_) => Instr::Expr(Node::Constant(Value::Unit)),
            Stmt::Var(x, flags, _) => {
                if flags.contains(ASTFlags::EXPORTED) {
                    return unsupported("export");
                }
                let (ident, value, _) = &**x;
                let value = self.expr(value)?;
                let slot = self.slots;
                self.slots += 1;
                self.scopes
                    .last_mut()
                    .expect("a block is open")
                    .push((ident.name.to_string(), slot));
                Instr::Set(slot, value)
            }
            Stmt::Assignment(x) => {
                let (op, BinaryExpr { lhs, rhs }) = &**x;
                let op = match op.get_op_assignment_info() {
                    None => None,
                    Some((.., token, _)) => Some(
                        Op::of(token)
                            .filter(|o| {
                                matches!(
                                    o,
                                    Op::Add | Op::Sub | Op::Mul | Op::Div | Op::Rem | Op::Pow
                                )
                            })
                            .ok_or_else(|| format!("the op-assignment `{token}=`"))?,
                    ),
                };
                let rhs = self.expr(rhs)?;
                match lhs {
                    Expr::Variable(v, _, _) if v.2.is_empty() => {
                        let Some(slot) = self.local(&v.1) else {
                            return unsupported(format!("an assignment to `{}`", v.1));
                        };
                        match op {
                            None => Instr::Set(slot, rhs),
                            Some(op) => Instr::Update(slot, op, rhs),
                        }
                    }
                    Expr::Dot(d, _, _)
                        if self.is_parameter(&d.lhs, AIR_BRAKES)
                            && property(&d.rhs) == Some("deployment_level") =>
                    {
                        match op {
                            None => Instr::SetLevel(rhs),
                            Some(op) => Instr::UpdateLevel(op, rhs),
                        }
                    }
                    _ => {
                        return unsupported(
                            "an assignment to anything but a local variable or `air_brakes.deployment_level`",
                        );
                    }
                }
            }
            Stmt::If(x, _) => {
                let condition = self.expr(&x.expr)?;
                let then = self.block(x.body.statements())?;
                let otherwise = self.block(x.branch.statements())?;
                Instr::If(condition, then, otherwise)
            }
            Stmt::Return(value, flags, _) => {
                if flags.contains(ASTFlags::BREAK) {
                    return unsupported("throw");
                }
                Instr::Return(value.as_deref().map(|e| self.expr(e)).transpose()?)
            }
            Stmt::Expr(e) => Instr::Expr(self.expr(e)?),
            Stmt::FnCall(call, _) => Instr::Expr(self.call(call)?),
            Stmt::Block(block) => Instr::Block(self.block(block.statements())?),
            _ => return unsupported("a loop, switch, try, import or closure"),
        })
    }

    fn is_parameter(&self, expr: &Expr, index: usize) -> bool {
        matches!(expr, Expr::Variable(v, _, _)
            if v.2.is_empty() && self.local(&v.1).is_none() && self.parameter(&v.1) == Some(index))
    }

    fn expr(&mut self, expr: &Expr) -> Translated<Node> {
        self.nodes += 1;
        Ok(match expr {
            Expr::BoolConstant(b, _) => Node::Constant(Value::Bool(*b)),
            Expr::IntegerConstant(i, _) => Node::Constant(Value::Int(*i)),
            Expr::FloatConstant(f, _) => Node::Constant(Value::Float(**f)),
            Expr::Unit(_) => Node::Constant(Value::Unit),
            Expr::DynamicConstant(d, _) => Node::Constant(match scalar(d) {
                Some(v) => v,
                None => Value::Array(d.clone().into_array().map_err(|_| "a constant map")?),
            }),
            Expr::Variable(v, _, _) => {
                let (_, name, namespace, _) = &**v;
                if !namespace.is_empty() {
                    if namespace.path.len() != 1 {
                        return unsupported("a nested module path");
                    }
                    let module = namespace.root().to_owned();
                    let key = (module, name.to_string());
                    let index = match self.names.iter().position(|n| *n == key) {
                        Some(i) => i,
                        None => {
                            self.names.push(key);
                            self.names.len() - 1
                        }
                    };
                    return Ok(Node::Name(index));
                }
                if let Some(slot) = self.local(name) {
                    return Ok(Node::Local(slot));
                }
                match self.parameter(name) {
                    Some(TIME) => Node::Time,
                    Some(SAMPLING_RATE) => Node::SamplingRate,
                    Some(STATE) => Node::Row(Row::State),
                    _ => return unsupported(format!("the argument `{name}` as a value")),
                }
            }
            Expr::Index(x, flags, _) => {
                if flags.contains(ASTFlags::NEGATED) {
                    return unsupported("`?[`");
                }
                self.index(&x.lhs, &x.rhs, flags.contains(ASTFlags::BREAK))?
            }
            Expr::Dot(x, flags, _) => {
                if flags.contains(ASTFlags::NEGATED) {
                    return unsupported("`?.`");
                }
                self.dot(&x.lhs, &x.rhs)?
            }
            Expr::FnCall(call, _) => self.call(call)?,
            Expr::And(x, _) => Node::And(self.exprs(x)?),
            Expr::Or(x, _) => Node::Or(self.exprs(x)?),
            Expr::Array(items, _) => Node::Array(self.exprs(items)?),
            Expr::Stmt(block) => Node::Block(self.block(block.statements())?),
            _ => return unsupported("a string, map, closure, `this`, `??` or custom expression"),
        })
    }

    fn exprs(&mut self, exprs: &[Expr]) -> Translated<Box<[Node]>> {
        exprs
            .iter()
            .map(|e| self.expr(e))
            .collect::<Translated<Vec<_>>>()
            .map(Vec::into_boxed_slice)
    }

    /// `lhs[...]`: in Rhai's AST the last link of a chain carries [`ASTFlags::BREAK`] and
    /// holds the index itself; a link without it holds the next link, whose left side is
    /// this link's index (`a[i][j]` is `Index(a, Index(i, j, BREAK))`).
    fn index(&mut self, lhs: &Expr, rhs: &Expr, last: bool) -> Translated<Node> {
        let (first, next) = if last {
            (rhs, None)
        } else {
            match rhs {
                Expr::Index(x, flags, _) if !flags.contains(ASTFlags::NEGATED) => {
                    (&x.lhs, Some((&x.rhs, flags.contains(ASTFlags::BREAK))))
                }
                _ => return unsupported("a property of an indexed value"),
            }
        };
        let Expr::IntegerConstant(i, _) = first else {
            return unsupported("an index that is not an integer literal");
        };
        let mut node = if self.is_parameter(lhs, STATE_HISTORY) {
            if *i != -1 && *i != 0 {
                return unsupported("`state_history` at an index other than -1 or 0");
            }
            Node::Row(Row::Last)
        } else {
            Node::Index(Box::new(self.expr(lhs)?), *i)
        };
        let mut next = next;
        while let Some((link, last)) = next {
            let (index, following) = if last {
                (link, None)
            } else {
                match link {
                    Expr::Index(x, flags, _) if !flags.contains(ASTFlags::NEGATED) => {
                        (&x.lhs, Some((&x.rhs, flags.contains(ASTFlags::BREAK))))
                    }
                    _ => return unsupported("a property of an indexed value"),
                }
            };
            let Expr::IntegerConstant(j, _) = index else {
                return unsupported("an index that is not an integer literal");
            };
            node = Node::Index(Box::new(node), *j);
            next = following;
        }
        Ok(node)
    }

    /// `lhs.rhs`: a property or a method of the air-brake or environment argument.
    fn dot(&mut self, lhs: &Expr, rhs: &Expr) -> Translated<Node> {
        if self.is_parameter(lhs, AIR_BRAKES) {
            return Ok(match rhs {
                Expr::Property(..) => match property(rhs) {
                    Some("deployment_level") => Node::Level,
                    Some("clamp") => Node::Clamp,
                    Some("override_rocket_drag") => Node::OverrideRocketDrag,
                    Some("reference_area") => Node::ReferenceArea,
                    _ => return unsupported("an unknown air-brake property"),
                },
                Expr::MethodCall(call, _)
                    if call.name == "drag_coefficient" && call.args.len() == 2 =>
                {
                    Node::DragCoefficient(
                        Box::new(self.expr(&call.args[0])?),
                        Box::new(self.expr(&call.args[1])?),
                    )
                }
                _ => return unsupported("an unknown air-brake method"),
            });
        }
        if self.is_parameter(lhs, ENVIRONMENT) {
            return Ok(match rhs {
                Expr::Property(..) if property(rhs) == Some("elevation") => Node::Elevation,
                Expr::MethodCall(call, _) if call.args.len() == 1 => {
                    let query = Query::of(&call.name).ok_or("an unknown environment method")?;
                    Node::Query(query, Box::new(self.expr(&call.args[0])?))
                }
                _ => return unsupported("an unknown environment property"),
            });
        }
        unsupported("a property or method of anything but `air_brakes` or `environment`")
    }

    fn call(&mut self, call: &FnCallExpr) -> Translated<Node> {
        if !call.namespace.is_empty() || call.capture_parent_scope {
            return unsupported("a qualified function call");
        }
        let args = &call.args;
        if let Some(token) = &call.op_token {
            return Ok(match (token, args.len()) {
                (Token::Minus | Token::UnaryMinus, 1) => {
                    Node::Negate(Box::new(self.expr(&args[0])?))
                }
                (Token::Bang, 1) => Node::Not(Box::new(self.expr(&args[0])?)),
                (token, 2) => {
                    let op = Op::of(token).ok_or_else(|| format!("the operator `{token}`"))?;
                    Node::Binary(
                        op,
                        Box::new(self.expr(&args[0])?),
                        Box::new(self.expr(&args[1])?),
                    )
                }
                _ => return unsupported(format!("the operator `{token}`")),
            });
        }
        match (Math::of(&call.name), args.len()) {
            (Some(math), 1) => Ok(Node::Math(math, Box::new(self.expr(&args[0])?))),
            _ => unsupported(format!("the function `{}`", call.name)),
        }
    }
}

/// The property name of a `Property` expression.
fn property(expr: &Expr) -> Option<&str> {
    match expr {
        Expr::Property(p, _) => Some(p.2.as_str()),
        _ => None,
    }
}

/// A scalar `Dynamic` as a value.
fn scalar(value: &Dynamic) -> Option<Value> {
    if value.is_unit() {
        Some(Value::Unit)
    } else if let Ok(b) = value.as_bool() {
        Some(Value::Bool(b))
    } else if let Ok(i) = value.as_int() {
        Some(Value::Int(i))
    } else {
        value.as_float().ok().map(Value::Float)
    }
}

/// Compiles `controller_function` of `ast`, or says why it stays with the interpreter.
pub(crate) fn compile(ast: &AST, function: &str) -> Result<Compiled, String> {
    let mut functions = ast.iter_fn_def();
    let (Some(def), None) = (functions.next(), functions.next()) else {
        return unsupported("functions besides `controller_function`");
    };
    if def.name != function {
        return unsupported("functions besides `controller_function`");
    }
    let params: Vec<String> = def.params.iter().map(ToString::to_string).collect();
    let mut translator = Translator {
        params: &params,
        scopes: vec![Vec::new()],
        slots: 0,
        names: Vec::new(),
        nodes: 0,
    };
    // The walk of a functions-only AST visits the statements of the one function body at
    // depth 1, in order.
    let mut body = Vec::new();
    let mut failure = None;
    ast.clone_functions_only().walk(&mut |path: &[ASTNode]| {
        if let [ASTNode::Stmt(statement)] = path {
            match translator.statement(statement) {
                Ok(instr) => body.push(instr),
                Err(why) => {
                    failure = Some(why);
                    return false;
                }
            }
        }
        true
    });
    if let Some(why) = failure {
        return Err(why);
    }
    let body = Block(body.into_boxed_slice());
    // Rhai counts an operation per statement and expression it evaluates (a few for a
    // native call); without loops a call evaluates each node at most once, so a body this
    // small can never reach the sandbox's limit.
    if (translator.nodes as u64).saturating_mul(OPERATIONS_PER_NODE) >= sandbox::MAX_OPERATIONS {
        return unsupported("a body too long to be sure of the operation limit");
    }
    Ok(Compiled {
        body,
        slots: translator.slots,
        names: translator.names,
    })
}

/// A float argument of a native function (the registered functions take `FLOAT` only).
fn float(value: &Value) -> Result<FLOAT, Bail> {
    match value {
        Value::Float(x) => Ok(*x),
        _ => Err(Bail),
    }
}

fn boolean(value: &Value) -> Result<bool, Bail> {
    match value {
        Value::Bool(b) => Ok(*b),
        _ => Err(Bail),
    }
}

/// Element `i` (negative from the end) of `len` elements.
fn element(i: INT, len: usize) -> Result<usize, Bail> {
    let len = INT::try_from(len).map_err(|_| Bail)?;
    let at = if i < 0 { len + i } else { i };
    if (0..len).contains(&at) {
        usize::try_from(at).map_err(|_| Bail)
    } else {
        Err(Bail)
    }
}

impl Frame<'_, '_> {
    fn row(&self, row: Row) -> &[FLOAT] {
        match row {
            Row::State => self.inputs.state,
            Row::Last => self.inputs.last_row,
        }
    }

    fn eval(&mut self, node: &Node) -> Result<Value, Bail> {
        let inputs = self.inputs;
        Ok(match node {
            Node::Constant(v) => v.clone(),
            Node::Local(slot) => self.locals[*slot].clone(),
            Node::Name(i) => self.names[*i].clone(),
            Node::Time => Value::Float(inputs.time),
            Node::SamplingRate => Value::Float(inputs.sampling_rate),
            Node::Row(row) => Value::Row(*row),
            Node::Index(base, i) => match self.eval(base)? {
                Value::Row(row) => {
                    let values = self.row(row);
                    Value::Float(values[element(*i, values.len())?])
                }
                Value::Array(items) => scalar(&items[element(*i, items.len())?]).ok_or(Bail)?,
                _ => return Err(Bail),
            },
            Node::Binary(op, a, b) => {
                let a = self.eval(a)?;
                let b = self.eval(b)?;
                op.apply(&a, &b)?
            }
            Node::Negate(a) => match self.eval(a)? {
                Value::Float(x) => Value::Float(-x),
                Value::Int(i) => Value::Int(i.checked_neg().ok_or(Bail)?),
                _ => return Err(Bail),
            },
            Node::Not(a) => Value::Bool(!boolean(&self.eval(a)?)?),
            Node::And(items) => {
                for item in &**items {
                    if !boolean(&self.eval(item)?)? {
                        return Ok(Value::Bool(false));
                    }
                }
                Value::Bool(true)
            }
            Node::Or(items) => {
                for item in &**items {
                    if boolean(&self.eval(item)?)? {
                        return Ok(Value::Bool(true));
                    }
                }
                Value::Bool(false)
            }
            Node::Math(f, a) => Value::Float(f.apply(float(&self.eval(a)?)?)),
            Node::Query(q, h) => Value::Float(q.at(inputs.environment, float(&self.eval(h)?)?)),
            Node::Elevation => Value::Float(inputs.environment.elevation()),
            Node::Level => Value::Float(self.level),
            Node::Clamp => Value::Bool(inputs.air_brakes.clamp),
            Node::OverrideRocketDrag => Value::Bool(inputs.air_brakes.override_rocket_drag),
            Node::ReferenceArea => Value::Float(inputs.air_brakes.reference_area),
            Node::DragCoefficient(level, mach) => {
                let level = float(&self.eval(level)?)?;
                let mach = float(&self.eval(mach)?)?;
                Value::Float((inputs.air_brakes.drag_coefficient)(level, mach))
            }
            Node::Array(items) => {
                let mut array = Array::with_capacity(items.len());
                for item in &**items {
                    array.push(dynamic(self.eval(item)?, inputs));
                }
                Value::Array(array)
            }
            Node::Block(block) => match self.block(block)? {
                Flow::Next(v) => v,
                // A `return` inside an expression block is left to Rhai.
                Flow::Return(_) => return Err(Bail),
            },
        })
    }

    fn block(&mut self, block: &Block) -> Result<Flow, Bail> {
        let mut last = Value::Unit;
        for instr in &*block.0 {
            last = match instr {
                Instr::Set(slot, node) => {
                    let v = self.eval(node)?;
                    self.locals[*slot] = v;
                    Value::Unit
                }
                Instr::Update(slot, op, node) => {
                    let y = self.eval(node)?;
                    let x = float(&self.locals[*slot])?;
                    let v = op.apply(&Value::Float(x), &y)?;
                    self.locals[*slot] = v;
                    Value::Unit
                }
                Instr::SetLevel(node) => {
                    let v = float(&self.eval(node)?)?;
                    self.level = stored_level(self.inputs.air_brakes.clamp, v);
                    Value::Unit
                }
                Instr::UpdateLevel(op, node) => {
                    let y = self.eval(node)?;
                    let v = float(&op.apply(&Value::Float(self.level), &y)?)?;
                    self.level = stored_level(self.inputs.air_brakes.clamp, v);
                    Value::Unit
                }
                Instr::If(condition, then, otherwise) => {
                    let branch = if boolean(&self.eval(condition)?)? {
                        then
                    } else {
                        otherwise
                    };
                    match self.block(branch)? {
                        Flow::Next(v) => v,
                        flow @ Flow::Return(_) => return Ok(flow),
                    }
                }
                Instr::Block(inner) => match self.block(inner)? {
                    Flow::Next(v) => v,
                    flow @ Flow::Return(_) => return Ok(flow),
                },
                Instr::Return(value) => {
                    let v = match value {
                        Some(node) => self.eval(node)?,
                        None => Value::Unit,
                    };
                    return Ok(Flow::Return(v));
                }
                Instr::Expr(node) => self.eval(node)?,
            };
        }
        Ok(Flow::Next(last))
    }
}

/// A value as the `Dynamic` Rhai would hold.
fn dynamic(value: Value, inputs: &Inputs<'_>) -> Dynamic {
    match value {
        Value::Unit => Dynamic::UNIT,
        Value::Bool(b) => Dynamic::from_bool(b),
        Value::Int(i) => Dynamic::from_int(i),
        Value::Float(x) => Dynamic::from_float(x),
        Value::Row(row) => {
            let values: &[FLOAT] = match row {
                Row::State => inputs.state,
                Row::Last => inputs.last_row,
            };
            Dynamic::from_array(values.iter().map(|&v| Dynamic::from_float(v)).collect())
        }
        Value::Array(array) => Dynamic::from_array(array),
    }
}

/// A compiled controller bound to the values of its `global::`/`motor::` names, with its
/// frame's storage.
#[derive(Debug, Clone)]
pub(crate) struct Bound {
    compiled: Compiled,
    locals: Vec<Value>,
    names: Vec<Value>,
}

impl Compiled {
    /// Binds the names to their values (`lookup(namespace, name)`); `None` when one has no
    /// scalar value (the interpreter then runs every call).
    pub(crate) fn bind(&self, lookup: impl Fn(&str, &str) -> Option<Dynamic>) -> Option<Bound> {
        let names = self
            .names
            .iter()
            .map(|(namespace, name)| scalar(&lookup(namespace, name)?))
            .collect::<Option<_>>()?;
        Some(Bound {
            compiled: self.clone(),
            locals: vec![Value::Unit; self.slots],
            names,
        })
    }
}

impl Bound {
    /// Runs the call: the returned value and the level left, or [`Bail`].
    pub(crate) fn call(
        &mut self,
        inputs: &Inputs<'_>,
        level: FLOAT,
    ) -> Result<(Dynamic, FLOAT), Bail> {
        let mut frame = Frame {
            inputs,
            locals: &mut self.locals,
            names: &self.names,
            level,
        };
        let value = match frame.block(&self.compiled.body)? {
            Flow::Next(v) | Flow::Return(v) => v,
        };
        let level = frame.level;
        Ok((dynamic(value, inputs), level))
    }
}
