//! Scene errors that point at the file, line, column and field.

use std::fmt;

use super::rules::BuildError;
pub use super::rules::number;

/// One problem in a scene file.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// File name as given by the user.
    pub file: String,
    /// 1-based line (0 when the problem is the file as a whole).
    pub line: usize,
    /// 1-based column in characters (0 when unknown).
    pub column: usize,
    /// Dotted path of the field, e.g. `puck[2].beta` (empty for syntax).
    pub field: String,
    /// What is wrong and what would be right.
    pub message: String,
    /// The scene rule broken, when it is one (`None` for syntax, types,
    /// unknown keys and the file as a whole): what a caller tells kinds
    /// apart by (Python's exception class).
    pub rule: Option<BuildError>,
}

impl SceneError {
    /// An error at byte offset `offset` of `text`.
    #[must_use]
    pub fn at(file: &str, text: &str, offset: usize, field: &str, message: String) -> Self {
        let (line, column) = line_column(text, offset);
        Self {
            file: file.to_owned(),
            line,
            column,
            field: one_line(field),
            message: one_line(&message),
            rule: None,
        }
    }

    /// This error as the breaking of `rule`.
    #[must_use]
    pub fn breaking(self, rule: BuildError) -> Self {
        Self {
            rule: Some(rule),
            ..self
        }
    }

    /// An error about the whole file (unreadable, empty …).
    #[must_use]
    pub fn whole_file(file: &str, message: String) -> Self {
        Self {
            file: file.to_owned(),
            line: 0,
            column: 0,
            field: String::new(),
            message: one_line(&message),
            rule: None,
        }
    }
}

impl fmt::Display for SceneError {
    /// `file:line:column: field: message`, the form editors jump to.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if self.line > 0 {
            write!(f, ":{}:{}", self.line, self.column)?;
        }
        if !self.field.is_empty() {
            write!(f, ": {}", self.field)?;
        }
        write!(f, ": {}", self.message)
    }
}

/// Every problem found in one scene file (never empty).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneErrors(pub Vec<SceneError>);

impl SceneErrors {
    /// A list of one.
    #[must_use]
    pub fn single(e: SceneError) -> Self {
        Self(vec![e])
    }
}

impl fmt::Display for SceneErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneErrors {}

/// Longest message kept, in characters (a value quoted from the file may be
/// huge).
const MAX_MESSAGE: usize = 400;

/// A message fit for one line of a terminal: control characters (a newline
/// inside a string value) escaped, numbers of more than 24 characters
/// (`0.000…0001` for 1e-300) written as [`number`] writes them, and cut at
/// [`MAX_MESSAGE`] characters.
pub fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut token = String::new();
    let flush = |token: &mut String, out: &mut String| {
        match token.parse::<f64>() {
            Ok(x) if token.len() > 24 => out.push_str(&number(x)),
            _ => out.push_str(token),
        }
        token.clear();
    };
    let mut prev = ' ';
    for c in text.chars() {
        // Digits inside a word (a name such as `p12345…`) are not a number.
        let in_word = token.is_empty() && (prev.is_alphanumeric() || prev == '_');
        prev = c;
        let numeric = !in_word
            && (c.is_ascii_digit()
                || (!token.is_empty() && matches!(c, '.' | 'e' | 'E' | '+' | '-'))
                || (token.is_empty() && matches!(c, '-' | '.')));
        if numeric {
            token.push(c);
            continue;
        }
        flush(&mut token, &mut out);
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    flush(&mut token, &mut out);
    if out.chars().count() > MAX_MESSAGE {
        out = out.chars().take(MAX_MESSAGE).collect::<String>() + "…";
    }
    out
}

/// 1-based line and character column of byte `offset` in `text`.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_are_one_based() {
        let text = "a = 1\nbé = 2\n";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 6), (2, 1));
        assert_eq!(line_column(text, 9), (2, 3)); // after the two-byte é
        assert_eq!(line_column(text, 999), (3, 1));
    }

    #[test]
    fn messages_stay_on_one_short_line() {
        let tiny = format!("{}", 1e-300);
        assert!(tiny.len() > 300);
        assert_eq!(
            one_line(&format!("{tiny} is too small")),
            "1e-300 is too small"
        );
        assert_eq!(one_line("name \"a\nb\""), "name \"a\\nb\"");
        assert_eq!(
            one_line("puck[12].position: 0.5 and -3"),
            "puck[12].position: 0.5 and -3"
        );
        assert_eq!(one_line(&"x".repeat(1000)).chars().count(), MAX_MESSAGE + 1);
        let name = format!("name \"p{}\"", "1".repeat(30));
        assert_eq!(one_line(&name), name);
        assert_eq!(number(1.42), "1.42");
        assert_eq!(number(2.5e20), "2.5e20");
        assert_eq!(number(-1e-300), "-1e-300");
    }
}
