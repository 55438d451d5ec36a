//! A request's JSON arguments bound and read as Python binds and
//! converts a method's (positional ones in order, then keywords by name;
//! a vector from any list of numbers), with Python's `TypeError` words
//! when they do not fit.

use serde_json::{Map, Value};

use crate::error::{ErrorKind, WorldError, WorldResult};

pub(crate) fn type_error(message: String) -> WorldError {
    WorldError::new(ErrorKind::Type, message)
}

/// A request's arguments bound to a method's parameters, as Python binds
/// them: positional ones in order, then keywords by name.
pub(crate) struct Bound<'a> {
    class: &'static str,
    op: &'a str,
    params: &'static [&'static str],
    values: Vec<Option<&'a Value>>,
}

impl<'a> Bound<'a> {
    pub(crate) fn new(
        class: &'static str,
        op: &'a str,
        params: &'static [&'static str],
        args: &'a [Value],
        kwargs: &'a Map<String, Value>,
    ) -> WorldResult<Self> {
        if args.len() > params.len() {
            return Err(type_error(format!(
                "{class}.{op}() takes {} positional arguments but {} were given",
                params.len(),
                args.len()
            )));
        }
        let mut values: Vec<Option<&Value>> = vec![None; params.len()];
        for (slot, v) in values.iter_mut().zip(args) {
            *slot = Some(v);
        }
        for (k, v) in kwargs {
            let Some(i) = params.iter().position(|p| p == k) else {
                return Err(type_error(format!(
                    "{class}.{op}() got an unexpected keyword argument '{k}'"
                )));
            };
            if values[i].is_some() {
                return Err(type_error(format!(
                    "{class}.{op}() got multiple values for argument '{k}'"
                )));
            }
            values[i] = Some(v);
        }
        Ok(Self {
            class,
            op,
            params,
            values,
        })
    }

    pub(crate) fn value(&self, i: usize) -> Option<&'a Value> {
        self.values[i]
    }

    pub(crate) fn missing(&self, i: usize) -> WorldError {
        type_error(format!(
            "{}.{}() missing 1 required positional argument: '{}'",
            self.class, self.op, self.params[i]
        ))
    }

    pub(crate) fn wrong(&self, i: usize, what: &str) -> WorldError {
        type_error(format!(
            "{}.{}(): argument '{}': give {what}",
            self.class, self.op, self.params[i]
        ))
    }

    /// Required argument `i`.
    pub(crate) fn req<T: FromArg>(&self, i: usize) -> WorldResult<T> {
        let value = self.values[i].ok_or_else(|| self.missing(i))?;
        T::from_arg(value).map_err(|what| self.wrong(i, what))
    }

    /// Optional argument `i` (`None` when not given or `None`).
    pub(crate) fn opt<T: FromArg>(&self, i: usize) -> WorldResult<Option<T>> {
        match self.values[i] {
            None | Some(Value::Null) => Ok(None),
            Some(v) => T::from_arg(v).map(Some).map_err(|what| self.wrong(i, what)),
        }
    }
}

/// The one value of an attribute set (`world.view = "split"`).
pub(crate) struct Arg<'a> {
    pub(crate) name: &'a str,
    pub(crate) value: &'a Value,
}

impl Arg<'_> {
    pub(crate) fn get<T: FromArg>(&self) -> WorldResult<T> {
        T::from_arg(self.value)
            .map_err(|what| type_error(format!("world.{} = : give {what}", self.name)))
    }
}

/// A vector as Python gives it: any sequence of `N` numbers.
pub(crate) struct Vector<const N: usize>(pub(crate) [f64; N]);

/// A value read from a request's JSON argument, or what it should have
/// been.
pub(crate) trait FromArg: Sized {
    fn from_arg(v: &Value) -> Result<Self, &'static str>;
}

impl FromArg for String {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        v.as_str().map(str::to_owned).ok_or("a str")
    }
}

impl FromArg for Value {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        Ok(v.clone())
    }
}

/// A number as Python gives a float: an int or a float, or a bool (an int
/// in Python, which pyo3 takes as 0.0 or 1.0).
fn number(v: &Value) -> Option<f64> {
    v.as_f64().or_else(|| v.as_bool().map(f64::from))
}

impl FromArg for f64 {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        number(v).ok_or("a number")
    }
}

impl FromArg for bool {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        v.as_bool().ok_or("True or False")
    }
}

impl FromArg for usize {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        v.as_u64()
            .or_else(|| v.as_bool().map(u64::from))
            .and_then(|n| usize::try_from(n).ok())
            .ok_or("a whole number ≥ 0")
    }
}

impl<T: FromArg> FromArg for Option<T> {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        match v {
            Value::Null => Ok(None),
            v => T::from_arg(v).map(Some),
        }
    }
}

impl FromArg for Vec<String> {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        const WHAT: &str = "a list of str";
        let items = v.as_array().ok_or(WHAT)?;
        items
            .iter()
            .map(|x| x.as_str().map(str::to_owned).ok_or(WHAT))
            .collect()
    }
}

impl FromArg for Vec<f64> {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        const WHAT: &str = "a list of numbers";
        let items = v.as_array().ok_or(WHAT)?;
        items.iter().map(|x| number(x).ok_or(WHAT)).collect()
    }
}

impl<const N: usize> FromArg for Vector<N> {
    fn from_arg(v: &Value) -> Result<Self, &'static str> {
        let what = if N == 2 {
            "2 numbers (a tuple, list or array)"
        } else {
            "3 numbers (a tuple, list or array)"
        };
        let items = v.as_array().filter(|a| a.len() == N).ok_or(what)?;
        let mut out = [0.0; N];
        for (slot, x) in out.iter_mut().zip(items) {
            *slot = number(x).ok_or(what)?;
        }
        Ok(Self(out))
    }
}
