//! The data of a scene file as the bindings hand it over (JSON, TOML or a Python mapping,
//! converted without checks), and Python's `repr` of it, which the format's messages quote.

use crate::error::{Error, Real};

/// A value of a scene's data: what JSON, TOML and Python's plain types hold, and a
/// [`Foreign`] fallback for anything else a binding meets.
#[derive(Debug)]
pub enum Value {
    /// `null` / `None`.
    Null,
    /// A boolean.
    Bool(bool),
    /// An integer that fits 64 bits.
    Int(i64),
    /// A larger integer: its decimal digits (with a sign) and its length in bits.
    BigInt {
        /// Decimal digits, as Python's `repr` writes them.
        digits: String,
        /// `int.bit_length()`.
        bits: u64,
    },
    /// A double.
    Float(f64),
    /// A string.
    Str(String),
    /// A list.
    List(Vec<Value>),
    /// A tuple (a list in every check; only its `repr` differs).
    Tuple(Vec<Value>),
    /// A mapping, its keys in order.
    Map(Vec<(Value, Value)>),
    /// Something else (a NumPy scalar or array, another mapping type, any object).
    Foreign(Box<Foreign>),
}

/// How a foreign value reads in messages; asked only when a message quotes it.
pub trait Describe {
    /// Python's `repr` of it.
    fn repr(&self) -> String;
    /// Python's `type(value).__name__`.
    fn type_name(&self) -> String;
    /// Python's `str` of it (a mapping key is named by it).
    fn str(&self) -> String {
        self.repr()
    }
}

/// A [`Describe`] known up front.
#[derive(Clone, Debug)]
pub struct Described {
    /// Its `repr`.
    pub repr: String,
    /// Its type's name.
    pub type_name: String,
}

impl Describe for Described {
    fn repr(&self) -> String {
        self.repr.clone()
    }
    fn type_name(&self) -> String {
        self.type_name.clone()
    }
}

/// What a foreign value can stand for where the format would take it.
#[derive(Debug)]
pub enum Like {
    /// Nothing: refused wherever it is.
    Nothing,
    /// A real number (a NumPy float or integer, any number `float()` reads).
    Real(f64),
    /// A pair of coordinates may be given as this sequence (a NumPy array).
    Array(Vec<Value>),
    /// A mapping (any mapping type).
    Map(Vec<(Value, Value)>),
}

/// A value no plain variant holds: how it reads, and what it stands for.
pub struct Foreign {
    /// Its `repr`, type name and `str`.
    pub describe: Box<dyn Describe>,
    /// Where the format may take it as a number, coordinates or a mapping.
    pub like: Like,
}

impl std::fmt::Debug for Foreign {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Foreign").field("repr", &self.describe.repr()).field("like", &self.like).finish()
    }
}

impl Value {
    /// A foreign value.
    pub fn foreign(describe: impl Describe + 'static, like: Like) -> Value {
        Value::Foreign(Box::new(Foreign { describe: Box::new(describe), like }))
    }

    /// The entries of a mapping (any mapping type).
    pub fn as_map(&self) -> Option<&[(Value, Value)]> {
        match self {
            Value::Map(m) => Some(m),
            Value::Foreign(f) => match &f.like {
                Like::Map(m) => Some(m),
                _ => None,
            },
            _ => None,
        }
    }

    /// The items of a list or tuple.
    pub fn as_list(&self) -> Option<&[Value]> {
        match self {
            Value::List(v) | Value::Tuple(v) => Some(v),
            _ => None,
        }
    }

    /// A string.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Value::Str(s) => Some(s),
            _ => None,
        }
    }

    /// A mapping's value at the string key `key`.
    pub fn get(&self, key: &str) -> Option<&Value> {
        self.as_map()?.iter().find(|(k, _)| k.as_str() == Some(key)).map(|(_, v)| v)
    }

    /// Python's `repr`.
    pub fn repr(&self) -> String {
        let mut s = String::new();
        self.write_repr(&mut s);
        s
    }

    fn write_repr(&self, s: &mut String) {
        use std::fmt::Write;
        match self {
            Value::Null => s.push_str("None"),
            Value::Bool(b) => s.push_str(if *b { "True" } else { "False" }),
            Value::Int(i) => write!(s, "{i}").expect("a string takes it"),
            Value::BigInt { digits, .. } => s.push_str(digits),
            Value::Float(x) => write!(s, "{}", float_repr(*x)).expect("a string takes it"),
            Value::Str(t) => s.push_str(&str_repr(t)),
            Value::List(v) => {
                s.push('[');
                items(s, v);
                s.push(']');
            }
            Value::Tuple(v) => {
                s.push('(');
                items(s, v);
                if v.len() == 1 {
                    s.push(',');
                }
                s.push(')');
            }
            Value::Map(m) => {
                s.push('{');
                for (i, (k, v)) in m.iter().enumerate() {
                    if i > 0 {
                        s.push_str(", ");
                    }
                    k.write_repr(s);
                    s.push_str(": ");
                    v.write_repr(s);
                }
                s.push('}');
            }
            Value::Foreign(f) => s.push_str(&f.describe.repr()),
        }
    }

    /// Python's `str` (how a mapping key names its entry).
    pub fn str(&self) -> String {
        match self {
            Value::Str(t) => t.clone(),
            Value::Foreign(f) => f.describe.str(),
            _ => self.repr(),
        }
    }

    /// Python's `type(value).__name__` of what a binding converted.
    pub fn type_name(&self) -> String {
        match self {
            Value::Null => "NoneType".into(),
            Value::Bool(_) => "bool".into(),
            Value::Int(_) | Value::BigInt { .. } => "int".into(),
            Value::Float(_) => "float".into(),
            Value::Str(_) => "str".into(),
            Value::List(_) => "list".into(),
            Value::Tuple(_) => "tuple".into(),
            Value::Map(_) => "dict".into(),
            Value::Foreign(f) => f.describe.type_name(),
        }
    }
}

fn items(s: &mut String, v: &[Value]) {
    for (i, x) in v.iter().enumerate() {
        if i > 0 {
            s.push_str(", ");
        }
        x.write_repr(s);
    }
}

/// A double as Python's `repr` writes it (`1e-05`, `1e+16`, `-0.0`, `inf`, `nan`).
pub fn float_repr(x: f64) -> String {
    let s = Real(x).to_string();
    if x.is_finite() && !s.contains(['.', 'e']) {
        format!("{s}.0")
    } else {
        s
    }
}

/// A string as Python's `repr` writes it: single quotes unless it holds one and no double
/// quote; backslashes, the quote and control characters escaped.
pub fn str_repr(t: &str) -> String {
    let q = if t.contains('\'') && !t.contains('"') { '"' } else { '\'' };
    let mut s = String::with_capacity(t.len() + 2);
    s.push(q);
    for c in t.chars() {
        match c {
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            '\r' => s.push_str("\\r"),
            '\t' => s.push_str("\\t"),
            c if c == q => {
                s.push('\\');
                s.push(c);
            }
            c if (c as u32) < 0x20 || (0x7f..0xa0).contains(&(c as u32)) => {
                s.push_str(&format!("\\x{:02x}", c as u32));
            }
            c => s.push(c),
        }
    }
    s.push(q);
    s
}

/// A real number as Python's `float()` reads it for the format (not a bool or a string),
/// or the message Python gives, naming `name`.
pub(crate) fn real(name: &str, v: &Value) -> Result<f64, Error> {
    let bad = || Err(Error::invalid(name.to_owned(), "must be a real number", v.repr()));
    match v {
        Value::Float(x) => Ok(*x),
        Value::Int(i) => Ok(*i as f64),
        Value::BigInt { digits, bits } => match digits.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(Error::invalid(
                name.to_owned(),
                "must be a real number within the float range",
                format!("an integer of {bits} bits"),
            )),
        },
        Value::Foreign(f) => match f.like {
            Like::Real(x) => Ok(x),
            _ => bad(),
        },
        _ => bad(),
    }
}
