//! The scene file as written, with the byte span of every value, so that
//! validation can point at the line that holds a wrong number.

use serde::Deserialize;
use toml::Spanned;

use super::{SceneError, SceneErrors};

/// A value with its place in the file.
pub type At<T> = Spanned<T>;

/// Top level of a scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub title: Option<String>,
    pub description: Option<String>,
    pub c: Option<At<f64>>,
    pub before_start: Option<At<String>>,
    pub table: Option<RawTable>,
    pub physics: Option<RawPhysics>,
    pub effects: Option<RawEffects>,
    pub optics: Option<RawOptics>,
    #[serde(default)]
    pub puck: Vec<At<RawPuck>>,
    #[serde(default)]
    pub observer: Vec<At<RawObserver>>,
}

/// `[table]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTable {
    pub size: Option<At<Vec<f64>>>,
    pub cushion_restitution: Option<At<f64>>,
    pub friction: Option<At<f64>>,
    pub gravity: Option<At<f64>>,
}

/// `[physics]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPhysics {
    pub restitution: Option<At<f64>>,
}

/// `[effects]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEffects {
    pub contraction: Option<bool>,
    pub light_delay: Option<bool>,
    pub aberration: Option<bool>,
    pub doppler: Option<bool>,
    pub searchlight: Option<bool>,
    pub time_dilation: Option<bool>,
}

/// `[optics]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOptics {
    pub method: Option<At<String>>,
    pub history_frames: Option<At<i64>>,
    pub dichotomy_steps: Option<At<i64>>,
    pub interpolate: Option<bool>,
}

/// `[[puck]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawPuck {
    pub name: Option<At<String>>,
    pub position: At<Vec<f64>>,
    pub beta: Option<At<Vec<f64>>>,
    pub velocity: Option<At<Vec<f64>>>,
    pub u: Option<At<Vec<f64>>>,
    pub radius: Option<At<f64>>,
    pub height: Option<At<f64>>,
    pub mass: Option<At<f64>>,
    pub color: Option<At<String>>,
}

/// `[[observer]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObserver {
    pub name: Option<At<String>>,
    pub position: At<Vec<f64>>,
    pub look_at: Option<At<Vec<f64>>>,
    pub beta: Option<At<Vec<f64>>>,
    pub u: Option<At<Vec<f64>>>,
}

/// Parses the TOML, turning syntax and schema errors (unknown key, wrong
/// type, missing field, wrong array length, duplicate key) into a
/// [`SceneError`] located at its line and column and naming its field
/// (`puck[2].mass`).
pub fn parse(text: &str, file: &str) -> Result<RawScene, SceneErrors> {
    toml::from_str(text).map_err(|e| {
        let message = plain_words(e.message().trim());
        let error = match e.span() {
            Some(span) => {
                let (field, key) = field_at(text, span.clone());
                let message = match key {
                    Some(k) if message == "duplicate key" => {
                        format!("duplicate key `{k}`: give each key once per table")
                    }
                    _ => message,
                };
                SceneError::at(file, text, span.start, &field, message)
            }
            None => SceneError::whole_file(file, message),
        };
        SceneErrors::single(error)
    })
}

/// serde's type names in the words of the scene format.
fn plain_words(message: &str) -> String {
    message
        .replace("expected f64", "expected a number")
        .replace("expected i64", "expected a whole number")
        .replace("expected a sequence", "expected a list such as [1.0, 2.0]")
        .replace("expected a boolean", "expected true or false")
}

/// Whether byte offset `at` lies in `span` (an empty span holds its start).
fn holds(span: &std::ops::Range<usize>, at: usize) -> bool {
    span.start <= at && (at < span.end || span.is_empty() && at == span.start)
}

/// `path.key`, quoting a key that is not bare.
fn join(path: &str, key: &str) -> String {
    let bare = !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    let key = if bare {
        key.to_owned()
    } else {
        format!("{key:?}")
    };
    if path.is_empty() {
        key
    } else {
        format!("{path}.{key}")
    }
}

/// The dotted path (`puck[2].mass`, `table.size[1]`) of the innermost key
/// or value of the file at `span`; when none holds it (a key the parser
/// refused), the table whose header comes last before it, plus the key's
/// text. Also returns that text when it is a plain key.
fn field_at(text: &str, span: std::ops::Range<usize>) -> (String, Option<String>) {
    use toml::de::{DeTable, DeValue};

    /// Smallest key or value span holding the offset, and the last table
    /// header at or before it.
    #[derive(Default)]
    struct Found {
        inner: Option<(usize, String)>,
        header: Option<(usize, String)>,
    }
    fn visit(v: &toml::Spanned<DeValue<'_>>, path: &str, at: usize, found: &mut Found) {
        let s = v.span();
        if holds(&s, at) && found.inner.as_ref().is_none_or(|(len, _)| s.len() <= *len) {
            found.inner = Some((s.len(), path.to_owned()));
        }
        match v.get_ref() {
            DeValue::Table(t) => {
                if !path.is_empty()
                    && s.start <= at
                    && found
                        .header
                        .as_ref()
                        .is_none_or(|(start, _)| s.start >= *start)
                {
                    found.header = Some((s.start, path.to_owned()));
                }
                for (k, x) in t.iter() {
                    let p = join(path, k.get_ref());
                    let ks = k.span();
                    if holds(&ks, at)
                        && found.inner.as_ref().is_none_or(|(len, _)| ks.len() <= *len)
                    {
                        found.inner = Some((ks.len(), p.clone()));
                    }
                    visit(x, &p, at, found);
                }
            }
            DeValue::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    visit(x, &format!("{path}[{i}]"), at, found);
                }
            }
            _ => {}
        }
    }

    let key = text
        .get(span.clone())
        .map(str::trim)
        .filter(|k| {
            !k.is_empty()
                && k.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        })
        .map(str::to_owned);
    let (root, _) = DeTable::parse_recoverable(text);
    let root = toml::Spanned::new(root.span(), DeValue::Table(root.into_inner()));
    let mut found = Found::default();
    visit(&root, "", span.start, &mut found);
    let field = match (found.inner, found.header, &key) {
        (Some((_, path)), _, _) if !path.is_empty() => path,
        (_, Some((_, header)), Some(k)) if !header.ends_with(k.as_str()) => join(&header, k),
        (_, Some((_, header)), _) => header,
        (_, None, Some(k)) => k.clone(),
        _ => String::new(),
    };
    (field, key)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        match parse(text, "t.toml") {
            Ok(_) => panic!("{text:?} parsed"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn type_errors_name_the_field() {
        let text = "c = 1\n[[puck]]\nposition = [0.5, 0.5]\n\n[[puck]]\nposition = [1.5, 0.5]\nmass = \"heavy\"\n";
        assert_eq!(
            error(text),
            "t.toml:7:8: puck[1].mass: invalid type: string \"heavy\", expected a number"
        );
        let text = "[[observer]]\nposition = [0, 0, 1]\nlook_at = nan\n";
        assert!(
            error(text).starts_with(
                "t.toml:3:11: observer[0].look_at: invalid type: floating point `NaN`"
            ),
            "{}",
            error(text)
        );
        let text = "[effects]\ndoppler = [true]\n";
        assert!(
            error(text).starts_with(
                "t.toml:2:11: effects.doppler: invalid type: sequence, expected true or false"
            ),
            "{}",
            error(text)
        );
        let text = "[[puck]]\nposition = [0.5, \"x\"]\n";
        assert!(
            error(text).contains(": puck[0].position[1]: "),
            "{}",
            error(text)
        );
    }

    #[test]
    fn duplicate_keys_name_the_key() {
        let text = "c = 1\n[[puck]]\nposition = [0.5, 0.5]\nmass = 1\nmass = 2\n";
        assert_eq!(
            error(text),
            "t.toml:5:1: puck[0].mass: duplicate key `mass`: give each key once per table"
        );
        let text = "c = 1\nc = 2\n";
        assert_eq!(
            error(text),
            "t.toml:2:1: c: duplicate key `c`: give each key once per table"
        );
    }

    #[test]
    fn unknown_and_missing_fields_are_named() {
        let e = error("[[puck]]\nposition = [0.5, 0.5]\nspin = 3\n");
        assert!(
            e.starts_with("t.toml:3:1: puck[0].spin: unknown field `spin`"),
            "{e}"
        );
        let e = error("c = 1\n[[puck]]\nmass = 1\n");
        assert!(e.contains(": puck[0]: missing field `position`"), "{e}");
    }
}
