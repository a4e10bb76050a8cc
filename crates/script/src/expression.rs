//! Parachute trigger expressions: RocketPy's `trigger(p, h, y)` callable written as one
//! expression (mission-format.md, "Custom triggers"; docs/physics.md §17).
//!
//! The language is the common subset of Rhai and Python expressions, so an expression means
//! the same in both: float literals (`5.0`, `2.5e2`, `1e3`), the variables `p`, `h` and the 13
//! state components by name, `+ - * /`, unary `-` and `!`, one comparison
//! `< <= > >= == !=` (comparisons do not chain), `&&`, `||`, parentheses, `true`, `false`,
//! `abs`, `sqrt`, `min` and `max`, and the latest readings of the rocket's sensors
//! (RocketPy's `trigger(p, h, y, sensors)`): `sensors[i]` by index in `[[rocket.sensors]]`
//! order or `sensors.NAME` by name, RocketPy's `sensors[i].measurement` spelling accepted too,
//! a barometer's reading as it stands and a component of a three-component reading by a
//! literal index, `sensors[0][2]` or `sensors.imu[2]` (the sensors are known when the
//! expression is parsed, [`Expression::parse_with`], so an unknown name, an index past the
//! list or a component of a single number is a parse error). Rhai's precedence: unary operators bind tightest, then
//! `* /`, `+ -`, one comparison, `&&`, `||`. Numbers and booleans never mix, and the whole
//! expression is a boolean; both are checked when the expression is parsed, so evaluation
//! cannot fail. Arithmetic is IEEE 754: a division by zero gives ±inf or NaN; a literal
//! must be finite (`1e400` is refused, not read as infinity).
//!
//! Parsing and evaluation recurse, so the expression's depth is bounded by [`MAX_DEPTH`]:
//! at most that many nested parentheses, unary operators and function calls, and an
//! expression tree at most that many operators tall (a chain `a + b + c` is two levels, as
//! it evaluates as `(a + b) + c`). A deeper text is an error at the token that crosses the
//! limit, never a stack overflow. Values quoted back in errors are cut to
//! [`QUOTED_CHARS`] characters.
//!
//! ```
//! use karman_script::{Expression, TriggerInputs};
//!
//! let drogue = Expression::parse("vz < 5.0 && z > 300.0")?;
//! let mut state = [0.0; 13];
//! state[2] = 1200.0; // z
//! state[5] = 4.0;    // vz
//! assert!(drogue.evaluate(&TriggerInputs { pressure: 88_000.0, height: 1100.0, state }));
//! # Ok::<(), karman_script::ExpressionError>(())
//! ```

use std::cmp::Ordering;
use std::fmt;
use thiserror::Error;

/// The names of the 13 state components, in RocketPy's order `y[0] … y[12]`.
pub const STATE_NAMES: [&str; 13] = [
    "x", "y", "z", "vx", "vy", "vz", "e0", "e1", "e2", "e3", "wx", "wy", "wz",
];

/// The deepest nesting an expression may have: parentheses, unary operators and function
/// calls inside one another, and the height of its operator tree.
pub const MAX_DEPTH: usize = 64;

/// The most characters of a literal or name an error quotes; a longer one is cut and its
/// length stated.
pub const QUOTED_CHARS: usize = 32;

/// What a trigger expression reads at one sampling instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriggerInputs {
    /// `p`: the (noisy) pressure signal, Pa.
    pub pressure: f64,
    /// `h`: the barometric height above ground derived from it, m.
    pub height: f64,
    /// `x, y, z, vx, vy, vz, e0, e1, e2, e3, wx, wy, wz` (SI, `z` above sea level).
    pub state: [f64; 13],
}

/// A sensor as a trigger expression reads it: its name, its kind's name and the number of
/// components of its reading (1 for a barometer, 3 for the others).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SensorShape<'a> {
    /// The sensor's name.
    pub name: &'a str,
    /// Its kind's name, for messages.
    pub kind: &'a str,
    /// Components of its reading.
    pub components: usize,
}

/// The largest sensor index or component an expression may write (a larger literal is not
/// an index of any rocket's sensors).
const MAX_INDEX: usize = 1 << 20;

/// A syntax or type error of an expression, at a character of its text.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("character {column} of the expression: {message}")]
pub struct ExpressionError {
    /// 1-based position, in characters, of the offending token.
    pub column: usize,
    /// What is wrong.
    pub message: String,
}

/// The type of a sub-expression.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Type {
    Number,
    Boolean,
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Type::Number => "a number",
            Type::Boolean => "a boolean",
        })
    }
}

/// A value read by the evaluator: index into `[p, h, state…]`.
const PRESSURE: usize = 0;
const HEIGHT: usize = 1;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Function {
    Abs,
    Sqrt,
    Min,
    Max,
}

impl Function {
    fn named(name: &str) -> Option<(Function, usize)> {
        Some(match name {
            "abs" => (Function::Abs, 1),
            "sqrt" => (Function::Sqrt, 1),
            "min" => (Function::Min, 2),
            "max" => (Function::Max, 2),
            _ => return None,
        })
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Binary {
    Add,
    Sub,
    Mul,
    Div,
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
    Equal,
    NotEqual,
    And,
    Or,
}

/// A node of the checked expression tree.
#[derive(Debug, Clone, PartialEq)]
enum Node {
    Number(f64),
    Boolean(bool),
    /// Index into `[p, h, x, y, z, …]`.
    Variable(usize),
    /// Index into the sensor readings the expression reads ([`Expression::reads`]).
    Sensor(usize),
    Negate(Box<Node>),
    Not(Box<Node>),
    Call(Function, Vec<Node>),
    Binary(Binary, Box<Node>, Box<Node>),
}

/// A parsed, type-checked trigger expression.
#[derive(Debug, Clone, PartialEq)]
pub struct Expression {
    text: String,
    root: Node,
    /// The `(sensor, component)` pairs read, in order of first appearance.
    reads: Vec<(usize, usize)>,
}

/// What the evaluator reads: `[p, h, state…]` and the sensor readings of
/// [`Expression::reads`].
struct Values<'v> {
    base: [f64; 15],
    sensors: &'v [f64],
}

impl Expression {
    /// Parses and checks `text`.
    ///
    /// # Errors
    /// [`ExpressionError`] at the first token that is not in the language, a number used as a
    /// boolean (or the reverse), a chained comparison, an unknown name or a wrong number of
    /// function arguments.
    pub fn parse(text: &str) -> Result<Self, ExpressionError> {
        Self::parse_with(text, &[])
    }

    /// Parses and checks `text` for a rocket with `sensors` (in `[[rocket.sensors]]` order).
    ///
    /// # Errors
    /// As [`Expression::parse`], and for a sensor that is not in `sensors` (a name, or an
    /// index past the list), a three-component reading used without a component, a component
    /// of a one-number reading or past the reading's components.
    pub fn parse_with(text: &str, sensors: &[SensorShape<'_>]) -> Result<Self, ExpressionError> {
        let tokens = tokenize(text)?;
        let mut parser = Parser {
            tokens: &tokens,
            next: 0,
            end: text.chars().count() + 1,
            depth: 0,
            sensors,
            reads: Vec::new(),
        };
        let (root, ty, _) = parser.or()?;
        if let Some(token) = parser.peek() {
            return Err(error(token.column, "unexpected text after the expression"));
        }
        if ty != Type::Boolean {
            return Err(error(
                1,
                "the expression is a number; a trigger must be a boolean",
            ));
        }
        Ok(Expression {
            text: text.to_owned(),
            root,
            reads: parser.reads,
        })
    }

    /// The `(sensor index, component)` pairs the expression reads, in order of first
    /// appearance: [`Expression::evaluate_with`] takes their values in this order.
    #[must_use]
    pub fn reads(&self) -> &[(usize, usize)] {
        &self.reads
    }

    /// The expression as written.
    #[must_use]
    pub fn text(&self) -> &str {
        &self.text
    }

    /// Whether the trigger fires for `inputs`.
    #[must_use]
    pub fn evaluate(&self, inputs: &TriggerInputs) -> bool {
        self.evaluate_with(inputs, &[])
    }

    /// Whether the trigger fires for `inputs` and the sensor readings `sensors`, one value
    /// per pair of [`Expression::reads`] in its order; a value missing from `sensors` (or a
    /// sensor not read yet, given as NaN) reads NaN, which no comparison but `!=` holds for.
    /// Allocation-free.
    #[must_use]
    pub fn evaluate_with(&self, inputs: &TriggerInputs, sensors: &[f64]) -> bool {
        let mut base = [0.0; 15];
        base[PRESSURE] = inputs.pressure;
        base[HEIGHT] = inputs.height;
        base[2..].copy_from_slice(&inputs.state);
        boolean(&self.root, &Values { base, sensors })
    }
}

fn number(node: &Node, values: &Values<'_>) -> f64 {
    match node {
        Node::Number(value) => *value,
        Node::Variable(index) => values.base[*index],
        Node::Sensor(slot) => values.sensors.get(*slot).copied().unwrap_or(f64::NAN),
        Node::Negate(inner) => -number(inner, values),
        Node::Call(function, args) => {
            let a = number(&args[0], values);
            match function {
                Function::Abs => a.abs(),
                Function::Sqrt => a.sqrt(),
                // Python's `min(a, b)` keeps `a` unless `b < a` (and `max` unless `b > a`);
                // Rhai's float `min`/`max` agree except on NaN.
                Function::Min => {
                    let b = number(&args[1], values);
                    if b < a { b } else { a }
                }
                Function::Max => {
                    let b = number(&args[1], values);
                    if b > a { b } else { a }
                }
            }
        }
        Node::Binary(op, a, b) => {
            let (a, b) = (number(a, values), number(b, values));
            match op {
                Binary::Add => a + b,
                Binary::Sub => a - b,
                Binary::Mul => a * b,
                _ => a / b,
            }
        }
        // The type check admits only numeric nodes here.
        Node::Boolean(_) | Node::Not(_) => f64::NAN,
    }
}

fn boolean(node: &Node, values: &Values<'_>) -> bool {
    match node {
        Node::Boolean(value) => *value,
        Node::Not(inner) => !boolean(inner, values),
        Node::Binary(Binary::And, a, b) => boolean(a, values) && boolean(b, values),
        Node::Binary(Binary::Or, a, b) => boolean(a, values) || boolean(b, values),
        Node::Binary(op @ (Binary::Equal | Binary::NotEqual), a, b) if is_boolean(a) => {
            (boolean(a, values) == boolean(b, values)) == (*op == Binary::Equal)
        }
        Node::Binary(op, a, b) => {
            let (a, b) = (number(a, values), number(b, values));
            match op {
                Binary::Less => a < b,
                Binary::LessEqual => a <= b,
                Binary::Greater => a > b,
                Binary::GreaterEqual => a >= b,
                // IEEE equality: NaN equals nothing, −0 equals +0.
                Binary::Equal => a.partial_cmp(&b) == Some(Ordering::Equal),
                _ => a.partial_cmp(&b) != Some(Ordering::Equal),
            }
        }
        // The type check admits only boolean nodes here.
        Node::Number(_)
        | Node::Variable(_)
        | Node::Sensor(_)
        | Node::Negate(_)
        | Node::Call(..) => false,
    }
}

/// Whether a checked node is boolean-valued.
fn is_boolean(node: &Node) -> bool {
    match node {
        Node::Boolean(_) | Node::Not(_) => true,
        Node::Binary(op, ..) => {
            !matches!(op, Binary::Add | Binary::Sub | Binary::Mul | Binary::Div)
        }
        Node::Number(_)
        | Node::Variable(_)
        | Node::Sensor(_)
        | Node::Negate(_)
        | Node::Call(..) => false,
    }
}

/// `text` as an error quotes it: at most [`QUOTED_CHARS`] characters, control characters
/// escaped, and the length of what was cut.
fn quoted(text: &str) -> String {
    let count = text.chars().count();
    let head: String = text.chars().take(QUOTED_CHARS).collect();
    let head = head.escape_debug().to_string();
    if count > QUOTED_CHARS {
        format!("{head}… ({count} characters)")
    } else {
        head
    }
}

/// The error of a text nested deeper than [`MAX_DEPTH`].
fn too_deep(column: usize) -> ExpressionError {
    error(
        column,
        format!(
            "the expression nests deeper than {MAX_DEPTH} levels (parentheses, unary \
             operators, function calls and chained operators each count)"
        ),
    )
}

fn error(column: usize, message: impl Into<String>) -> ExpressionError {
    ExpressionError {
        column,
        message: message.into(),
    }
}

#[derive(Debug, Clone, PartialEq)]
enum TokenKind {
    Number(f64),
    /// Digits inside brackets: a sensor index or a component.
    Index(usize),
    Name(String),
    /// An operator or punctuation: `+ - * / ( ) , < <= > >= == != && || ! [ ] .`.
    Symbol(&'static str),
}

#[derive(Debug, Clone, PartialEq)]
struct Token {
    kind: TokenKind,
    column: usize,
}

const SYMBOLS: [&str; 19] = [
    "<=", ">=", "==", "!=", "&&", "||", "+", "-", "*", "/", "(", ")", ",", "<", ">", "!", "[", "]",
    ".",
];

fn tokenize(text: &str) -> Result<Vec<Token>, ExpressionError> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let column = i + 1;
        let member = c == '.'
            && chars
                .get(i + 1)
                .is_some_and(|n| n.is_ascii_alphabetic() || *n == '_');
        let in_brackets = matches!(
            tokens.last(),
            Some(Token {
                kind: TokenKind::Symbol("["),
                ..
            })
        );
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit() && in_brackets {
            // An index: digits only (a float or a name inside brackets is refused by the
            // parser, which expects an index there).
            let start = i;
            while i < chars.len() && chars[i].is_ascii_alphanumeric() {
                i += 1;
            }
            let literal: String = chars[start..i].iter().collect();
            let index = literal
                .parse::<usize>()
                .ok()
                .filter(|n| *n <= MAX_INDEX)
                .ok_or_else(|| {
                    let literal = quoted(&literal);
                    error(
                        column,
                        format!("`{literal}` is not an index (digits, at most {MAX_INDEX})"),
                    )
                })?;
            tokens.push(Token {
                kind: TokenKind::Index(index),
                column,
            });
        } else if (c.is_ascii_digit() || c == '.') && !member {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '.') {
                // An exponent sign belongs to the literal.
                if matches!(chars[i], 'e' | 'E') && matches!(chars.get(i + 1), Some('+' | '-')) {
                    i += 1;
                }
                i += 1;
            }
            let literal: String = chars[start..i].iter().collect();
            tokens.push(Token {
                kind: TokenKind::Number(float_literal(&literal, column)?),
                column,
            });
        } else if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            tokens.push(Token {
                kind: TokenKind::Name(chars[start..i].iter().collect()),
                column,
            });
        } else {
            let rest: String = chars[i..chars.len().min(i + 2)].iter().collect();
            let Some(symbol) = SYMBOLS.iter().find(|s| rest.starts_with(**s)) else {
                let c = c.escape_debug();
                return Err(error(column, format!("`{c}` is not part of the language")));
            };
            i += symbol.chars().count();
            tokens.push(Token {
                kind: TokenKind::Symbol(symbol),
                column,
            });
        }
    }
    Ok(tokens)
}

/// A float literal of the common subset: digits, then a fraction `.digits` and/or an
/// exponent `e[+-]digits` (at least one of the two, so that Rhai reads a float, not an
/// integer).
fn float_literal(literal: &str, column: usize) -> Result<f64, ExpressionError> {
    let bad = |why: &str| {
        let literal = quoted(literal);
        error(column, format!("`{literal}` is not a float literal: {why}"))
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    let (mantissa, exponent) = match literal.find(['e', 'E']) {
        Some(at) => (&literal[..at], Some(&literal[at + 1..])),
        None => (literal, None),
    };
    let (whole, fraction) = match mantissa.split_once('.') {
        Some((whole, fraction)) => (whole, Some(fraction)),
        None => (mantissa, None),
    };
    if !digits(whole) {
        return Err(bad("write a digit before the point (0.5, not .5)"));
    }
    if let Some(fraction) = fraction
        && !digits(fraction)
    {
        return Err(bad("write a digit after the point (5.0, not 5.)"));
    }
    if let Some(exponent) = exponent {
        let unsigned = exponent.strip_prefix(['+', '-']).unwrap_or(exponent);
        if !digits(unsigned) {
            return Err(bad("the exponent needs digits"));
        }
    }
    if fraction.is_none() && exponent.is_none() {
        return Err(bad("integers are not numbers here; write 5.0"));
    }
    let value: f64 = literal.parse().map_err(|_| bad("cannot read it"))?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(bad("it is beyond the largest float, 1.8e308"))
    }
}

/// A parsed sub-expression: its node, its type and the height of its operator tree (1 for
/// a literal or a variable).
type Parsed = (Node, Type, usize);

struct Parser<'t> {
    tokens: &'t [Token],
    next: usize,
    /// Column just past the text, for errors at its end.
    end: usize,
    /// How many parentheses, unary operators and calls enclose the current token.
    depth: usize,
    /// The rocket's sensors.
    sensors: &'t [SensorShape<'t>],
    /// The `(sensor, component)` pairs read so far.
    reads: Vec<(usize, usize)>,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.next)
    }

    fn column(&self) -> usize {
        self.peek().map_or(self.end, |t| t.column)
    }

    fn symbol(&mut self, wanted: &[&'static str]) -> Option<(&'static str, usize)> {
        match self.peek() {
            Some(Token {
                kind: TokenKind::Symbol(s),
                column,
            }) if wanted.contains(s) => {
                let found = (*s, *column);
                self.next += 1;
                Some(found)
            }
            _ => None,
        }
    }

    /// Enters one more level of nesting at `column`, or refuses past [`MAX_DEPTH`]; the
    /// caller leaves it with `self.depth -= 1` once the nested part is parsed.
    fn enter(&mut self, column: usize) -> Result<(), ExpressionError> {
        if self.depth >= MAX_DEPTH {
            return Err(too_deep(column));
        }
        self.depth += 1;
        Ok(())
    }

    fn expect(&mut self, wanted: &'static str) -> Result<(), ExpressionError> {
        self.symbol(&[wanted])
            .map(|_| ())
            .ok_or_else(|| error(self.column(), format!("expected `{wanted}`")))
    }

    /// A binary level: `next (op next)*`, all operands of type `operand`.
    fn chain(
        &mut self,
        ops: &[&'static str],
        operand: Type,
        next: fn(&mut Self) -> Result<Parsed, ExpressionError>,
    ) -> Result<Parsed, ExpressionError> {
        let column = self.column();
        let (mut node, mut ty, mut height) = next(self)?;
        while let Some((op, at)) = self.symbol(ops) {
            check(ty, operand, column, op)?;
            let right_column = self.column();
            let (right, right_ty, right_height) = next(self)?;
            check(right_ty, operand, right_column, op)?;
            height = height.max(right_height) + 1;
            if height > MAX_DEPTH {
                return Err(too_deep(at));
            }
            node = Node::Binary(binary(op), Box::new(node), Box::new(right));
            ty = operand;
        }
        Ok((node, ty, height))
    }

    fn or(&mut self) -> Result<Parsed, ExpressionError> {
        self.chain(&["||"], Type::Boolean, Self::and)
    }

    fn and(&mut self) -> Result<Parsed, ExpressionError> {
        self.chain(&["&&"], Type::Boolean, Self::comparison)
    }

    fn comparison(&mut self) -> Result<Parsed, ExpressionError> {
        const OPS: [&str; 6] = ["<", "<=", ">", ">=", "==", "!="];
        let column = self.column();
        let (left, left_ty, left_height) = self.sum()?;
        let Some((op, at)) = self.symbol(&OPS) else {
            return Ok((left, left_ty, left_height));
        };
        let right_column = self.column();
        let (right, right_ty, right_height) = self.sum()?;
        let height = left_height.max(right_height) + 1;
        if height > MAX_DEPTH {
            return Err(too_deep(at));
        }
        if matches!(op, "==" | "!=") {
            if left_ty != right_ty {
                return Err(error(
                    at,
                    format!("`{op}` compares {left_ty} with {right_ty}"),
                ));
            }
        } else {
            check(left_ty, Type::Number, column, op)?;
            check(right_ty, Type::Number, right_column, op)?;
        }
        if let Some((_, again)) = self.symbol(&OPS) {
            return Err(error(
                again,
                "comparisons do not chain; write `a < b && b < c`",
            ));
        }
        Ok((
            Node::Binary(binary(op), Box::new(left), Box::new(right)),
            Type::Boolean,
            height,
        ))
    }

    fn sum(&mut self) -> Result<Parsed, ExpressionError> {
        self.chain(&["+", "-"], Type::Number, Self::product)
    }

    fn product(&mut self) -> Result<Parsed, ExpressionError> {
        self.chain(&["*", "/"], Type::Number, Self::unary)
    }

    fn unary(&mut self) -> Result<Parsed, ExpressionError> {
        if let Some((op, at)) = self.symbol(&["-", "!"]) {
            self.enter(at)?;
            let column = self.column();
            let (inner, ty, height) = self.unary()?;
            self.depth -= 1;
            let height = height + 1;
            if height > MAX_DEPTH {
                return Err(too_deep(at));
            }
            return Ok(if op == "-" {
                check(ty, Type::Number, column, "unary -")?;
                (Node::Negate(Box::new(inner)), Type::Number, height)
            } else {
                check(ty, Type::Boolean, column, "!")?;
                (Node::Not(Box::new(inner)), Type::Boolean, height)
            });
        }
        self.primary()
    }

    fn primary(&mut self) -> Result<Parsed, ExpressionError> {
        let column = self.column();
        let Some(token) = self.peek().cloned() else {
            return Err(error(self.end, "the expression ends too early"));
        };
        self.next += 1;
        match token.kind {
            TokenKind::Number(value) => Ok((Node::Number(value), Type::Number, 1)),
            TokenKind::Symbol("(") => {
                self.enter(column)?;
                let inner = self.or()?;
                self.expect(")")?;
                self.depth -= 1;
                Ok(inner)
            }
            TokenKind::Symbol(s) => Err(error(column, format!("unexpected `{s}`"))),
            TokenKind::Index(_) => Err(error(column, "unexpected index")),
            TokenKind::Name(name) if name == "sensors" => self.sensor(column),
            TokenKind::Name(name) => self.name(&name, column),
        }
    }

    fn name(&mut self, name: &str, column: usize) -> Result<Parsed, ExpressionError> {
        match name {
            "true" => return Ok((Node::Boolean(true), Type::Boolean, 1)),
            "false" => return Ok((Node::Boolean(false), Type::Boolean, 1)),
            "p" => return Ok((Node::Variable(PRESSURE), Type::Number, 1)),
            "h" => return Ok((Node::Variable(HEIGHT), Type::Number, 1)),
            _ => {}
        }
        if let Some(index) = STATE_NAMES.iter().position(|n| *n == name) {
            return Ok((Node::Variable(index + 2), Type::Number, 1));
        }
        let Some((function, arity)) = Function::named(name) else {
            let name = quoted(name);
            return Err(error(
                column,
                format!(
                    "unknown name `{name}` (variables: p, h, {}, sensors[i], sensors.NAME; \
                     functions: abs, sqrt, min, max)",
                    STATE_NAMES.join(", ")
                ),
            ));
        };
        self.expect("(")?;
        self.enter(column)?;
        let mut args = Vec::with_capacity(arity);
        let mut height = 1;
        loop {
            let arg_column = self.column();
            let (arg, ty, arg_height) = self.or()?;
            check(ty, Type::Number, arg_column, name)?;
            args.push(arg);
            height = height.max(arg_height + 1);
            if height > MAX_DEPTH {
                return Err(too_deep(column));
            }
            if self.symbol(&[","]).is_none() {
                break;
            }
            // Stop at the first argument past the arity rather than collecting thousands.
            if args.len() == arity {
                return Err(error(
                    column,
                    format!("`{name}` takes {arity} argument(s), got more"),
                ));
            }
        }
        self.expect(")")?;
        self.depth -= 1;
        if args.len() != arity {
            return Err(error(
                column,
                format!("`{name}` takes {arity} argument(s), got {}", args.len()),
            ));
        }
        Ok((Node::Call(function, args), Type::Number, height))
    }
}

impl Parser<'_> {
    /// An index in brackets, the `[` already read at `open`.
    fn index(&mut self, open: usize) -> Result<(usize, usize), ExpressionError> {
        let column = self.column();
        let index = match self.peek() {
            Some(Token {
                kind: TokenKind::Index(index),
                ..
            }) => *index,
            _ => {
                return Err(error(
                    column,
                    "expected an index (digits, as in sensors[0])",
                ));
            }
        };
        self.next += 1;
        self.expect("]").map_err(|_| {
            error(
                self.column(),
                format!("expected `]` closing the `[` at character {open}"),
            )
        })?;
        Ok((index, column))
    }

    /// A sensor reading after the name `sensors` (at `column`): `[i]` or `.NAME`, RocketPy's
    /// `.measurement` optionally, then `[c]` for a component of a three-component reading.
    fn sensor(&mut self, column: usize) -> Result<Parsed, ExpressionError> {
        let listed = || {
            if self.sensors.is_empty() {
                "the rocket has no [[rocket.sensors]]".to_owned()
            } else {
                let names: Vec<String> = self
                    .sensors
                    .iter()
                    .enumerate()
                    .map(|(i, s)| format!("{i}: {}", quoted(s.name)))
                    .collect();
                format!("the rocket's sensors are {}", names.join(", "))
            }
        };
        let sensor = if let Some((_, open)) = self.symbol(&["["]) {
            let (index, at) = self.index(open)?;
            if index >= self.sensors.len() {
                return Err(error(
                    at,
                    format!("no sensor at index {index}: {}", listed()),
                ));
            }
            index
        } else if self.symbol(&["."]).is_some() {
            let at = self.column();
            let Some(Token {
                kind: TokenKind::Name(name),
                ..
            }) = self.peek().cloned()
            else {
                return Err(error(at, "expected a sensor's name after `sensors.`"));
            };
            self.next += 1;
            let Some(index) = self.sensors.iter().position(|s| s.name == name) else {
                let name = quoted(&name);
                return Err(error(at, format!("no sensor named `{name}`: {}", listed())));
            };
            index
        } else {
            return Err(error(
                self.column(),
                "`sensors` is read as sensors[i] (in [[rocket.sensors]] order) or sensors.NAME",
            ));
        };
        // RocketPy's spelling, `sensors[i].measurement`.
        if let Some(Token {
            kind: TokenKind::Symbol("."),
            ..
        }) = self.peek()
            && matches!(
                self.tokens.get(self.next + 1),
                Some(Token { kind: TokenKind::Name(n), .. }) if n == "measurement"
            )
        {
            self.next += 2;
        }
        let shape = self.sensors[sensor];
        let name = quoted(shape.name);
        let component = if let Some((_, open)) = self.symbol(&["["]) {
            let (c, at) = self.index(open)?;
            if shape.components < 2 {
                return Err(error(
                    at,
                    format!(
                        "sensor `{name}` ({}) reads one number: it has no components; \
                         write it without `[{c}]`",
                        shape.kind
                    ),
                ));
            }
            if c >= shape.components {
                return Err(error(
                    at,
                    format!(
                        "sensor `{name}` ({}) has components 0 to {}, not {c}",
                        shape.kind,
                        shape.components - 1
                    ),
                ));
            }
            c
        } else if shape.components > 1 {
            return Err(error(
                column,
                format!(
                    "sensor `{name}` ({}) reads {} numbers; pick one, as in `sensors.{name}[0]`",
                    shape.kind, shape.components
                ),
            ));
        } else {
            0
        };
        let slot = match self.reads.iter().position(|r| *r == (sensor, component)) {
            Some(slot) => slot,
            None => {
                self.reads.push((sensor, component));
                self.reads.len() - 1
            }
        };
        Ok((Node::Sensor(slot), Type::Number, 1))
    }
}

fn check(found: Type, wanted: Type, column: usize, op: &str) -> Result<(), ExpressionError> {
    if found == wanted {
        Ok(())
    } else {
        Err(error(
            column,
            format!("`{op}` takes {wanted}, found {found}"),
        ))
    }
}

fn binary(op: &str) -> Binary {
    match op {
        "+" => Binary::Add,
        "-" => Binary::Sub,
        "*" => Binary::Mul,
        "/" => Binary::Div,
        "<" => Binary::Less,
        "<=" => Binary::LessEqual,
        ">" => Binary::Greater,
        ">=" => Binary::GreaterEqual,
        "==" => Binary::Equal,
        "!=" => Binary::NotEqual,
        "&&" => Binary::And,
        _ => Binary::Or,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs(vz: f64, z: f64) -> TriggerInputs {
        let mut state = [0.0; 13];
        state[2] = z;
        state[5] = vz;
        TriggerInputs {
            pressure: 90_000.0,
            height: 1000.0,
            state,
        }
    }

    fn eval(text: &str, vz: f64, z: f64) -> bool {
        Expression::parse(text)
            .unwrap_or_else(|e| panic!("{text}: {e}"))
            .evaluate(&inputs(vz, z))
    }

    #[test]
    fn camoes_drogue() {
        let text = "vz < 5.0 && z > 300.0";
        assert!(eval(text, 4.9, 301.0));
        assert!(!eval(text, 5.0, 301.0));
        assert!(!eval(text, 4.0, 300.0));
    }

    #[test]
    fn precedence_is_rhai_s() {
        // Unary binds tightest, then * /, + -, one comparison, &&, ||.
        assert!(eval("-vz * 2.0 == -(vz * 2.0)", 3.0, 0.0));
        assert!(eval("1.0 + 2.0 * 3.0 == 7.0", 0.0, 0.0));
        assert!(eval("true || false && false", 0.0, 0.0));
        assert!(!eval("(true || false) && false", 0.0, 0.0));
        assert!(eval("!false && true", 0.0, 0.0));
        assert!(eval("8.0 / 2.0 / 2.0 == 2.0", 0.0, 0.0));
        assert!(eval("5.0 - 2.0 - 1.0 == 2.0", 0.0, 0.0));
    }

    #[test]
    fn variables_functions_and_ieee() {
        assert!(eval("p == 90000.0 && h == 1000.0", 0.0, 0.0));
        assert!(eval("abs(vz) == 3.0 && sqrt(z) == 3.0", -3.0, 9.0));
        assert!(eval("min(vz, z) == -3.0 && max(vz, z) == 9.0", -3.0, 9.0));
        assert!(eval("1.0 / 0.0 > 1e308", 0.0, 0.0));
        assert!(eval("2.5e2 == 250.0 && 1E-3 == 0.001", 0.0, 0.0));
        assert!(eval("true != false", 0.0, 0.0));
    }

    #[test]
    fn errors_are_located() {
        let column = |text: &str| Expression::parse(text).map(|_| ()).unwrap_err().column;
        assert_eq!(column("vz < 5"), 6);
        assert_eq!(column("vz < 5."), 6);
        assert_eq!(column("vz < .5"), 6);
        assert_eq!(column("a < b < c"), 1);
        assert_eq!(column("0.0 < vz < 1.0"), 10);
        assert_eq!(column("vz + 1.0"), 1);
        assert_eq!(column("!vz"), 2);
        assert_eq!(column("vz && true"), 1);
        assert_eq!(column("vz < 1.0 &&"), 12);
        assert_eq!(column("vz ** 2.0 > 1.0"), 5);
        assert_eq!(column("min(vz) > 1.0"), 1);
        assert_eq!(column("(vz < 1.0"), 10);
        assert_eq!(column("vz < 1.0)"), 9);
        assert_eq!(column("vz # 1.0"), 4);
        assert_eq!(column("true == 1.0"), 6);
        assert_eq!(column(""), 1);
    }

    const SENSORS: [SensorShape<'static>; 2] = [
        SensorShape {
            name: "baro",
            kind: "barometer",
            components: 1,
        },
        SensorShape {
            name: "imu",
            kind: "accelerometer",
            components: 3,
        },
    ];

    #[test]
    fn sensors_by_index_and_name() {
        let parse = |text: &str| {
            Expression::parse_with(text, &SENSORS).unwrap_or_else(|e| panic!("{text}: {e}"))
        };
        let e = parse("sensors[0] < 80000.0 && sensors.imu[2] > 1.0 && sensors[1][2] < 9.0");
        assert_eq!(e.reads(), &[(0, 0), (1, 2)]);
        let fires = |e: &Expression, values: &[f64]| e.evaluate_with(&inputs(0.0, 0.0), values);
        assert!(fires(&e, &[79_999.0, 5.0]));
        assert!(!fires(&e, &[80_001.0, 5.0]));
        // Before the first reading (NaN) no comparison holds.
        assert!(!fires(&e, &[f64::NAN, 5.0]));
        assert!(!fires(&e, &[]));
        let rocketpy = parse("sensors[0].measurement < 1.0 && sensors.imu.measurement[1] > 0.0");
        assert_eq!(rocketpy.reads(), &[(0, 0), (1, 1)]);
        assert!(fires(&rocketpy, &[0.5, 1.0]));
        // Mixed with the state and p.
        assert!(fires(&parse("sensors.baro == p"), &[90_000.0]));
    }

    #[test]
    fn sensor_errors_are_located() {
        let fail = |text: &str| {
            Expression::parse_with(text, &SENSORS)
                .map(|_| ())
                .expect_err(text)
        };
        let e = fail("sensors.bar < 1.0");
        assert_eq!(e.column, 9);
        assert!(e.message.contains("no sensor named `bar`"), "{}", e.message);
        assert!(e.message.contains("0: baro, 1: imu"), "{}", e.message);
        let e = fail("sensors[2] < 1.0");
        assert_eq!(e.column, 9);
        assert!(e.message.contains("no sensor at index 2"), "{}", e.message);
        let e = fail("sensors[0][1] < 1.0");
        assert_eq!(e.column, 12);
        assert!(e.message.contains("reads one number"), "{}", e.message);
        let e = fail("sensors.imu[3] < 1.0");
        assert!(e.message.contains("components 0 to 2"), "{}", e.message);
        let e = fail("sensors.imu < 1.0");
        assert!(e.message.contains("reads 3 numbers"), "{}", e.message);
        assert_eq!(fail("sensors < 1.0").column, 9);
        assert_eq!(fail("sensors[0.0] < 1.0").column, 10);
        assert_eq!(fail("sensors[0 < 1.0").column, 11);
        assert_eq!(fail("sensors[99999999999999999999] < 1.0").column, 9);
        let none = Expression::parse("sensors[0] < 1.0").expect_err("no sensors");
        assert!(
            none.message.contains("has no [[rocket.sensors]]"),
            "{}",
            none.message
        );
        // `.5` is still refused as a literal.
        assert_eq!(fail("vz < .5").column, 6);
    }
}
