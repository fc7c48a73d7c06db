//! An error or a warning with its place in a model's text: what every message about a file
//! carries, so it can be shown as `file:line:col` with the line and a caret under the token.
//! Its own file because both the text front end and the switched compiler (whose warnings
//! keep their places) use it.

use std::fmt;

/// One error with its place in the text.
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Located {
    /// The source's name.
    pub name: String,
    /// 1-based line of the offending token.
    pub line: usize,
    /// 1-based column (in characters) of the offending token.
    pub column: usize,
    /// How many characters to underline on that line (at least 1).
    pub width: usize,
    /// What is wrong.
    pub message: String,
    /// The text of the offending line, to show under the message.
    pub source_line: String,
}

/// Every error found in one source, in the order the front end reported them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LocatedErrors(pub Vec<Located>);

impl fmt::Display for Located {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let gutter = self.line.to_string();
        let pad = " ".repeat(gutter.len());
        writeln!(
            f,
            "{}:{}:{}: {}",
            self.name, self.line, self.column, self.message
        )?;
        writeln!(f, "{pad} |")?;
        writeln!(f, "{gutter} | {}", self.source_line)?;
        write!(
            f,
            "{pad} | {}{}",
            " ".repeat(self.column - 1),
            "^".repeat(self.width)
        )
    }
}

impl fmt::Display for LocatedErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, error) in self.0.iter().enumerate() {
            if k > 0 {
                writeln!(f)?;
            }
            write!(f, "{error}")?;
        }
        Ok(())
    }
}

impl std::error::Error for LocatedErrors {}
