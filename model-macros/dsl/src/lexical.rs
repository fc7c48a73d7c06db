//! What is wrong with a text that does not even split into tokens: the lexer of `proc_macro2`
//! only says "cannot parse string into token stream", so the text is scanned again here to
//! name the problem and the place (an unclosed bracket at its opening, an unterminated
//! comment at its `/*`, a character the DSL does not use).

/// A lexical problem: 1-based line and column (in characters) of its character, and what is wrong.
pub(crate) struct LexProblem {
    pub line: usize,
    pub column: usize,
    pub message: String,
}

/// The first lexical problem of `text`, scanning it as a `.dsl` file (or, with `rust`, as Rust
/// source, where quotes start character literals and lifetimes).
pub(crate) fn first_problem(text: &str, rust: bool) -> Option<LexProblem> {
    let chars: Vec<char> = text.chars().collect();
    // (line, column) of every character, 1-based.
    let mut places = Vec::with_capacity(chars.len() + 1);
    let (mut line, mut column) = (1, 1);
    for &c in &chars {
        places.push((line, column));
        if c == '\n' {
            line += 1;
            column = 1;
        } else {
            column += 1;
        }
    }
    places.push((line, column));
    let at = |k: usize, message: String| {
        let (line, column) = places[k];
        Some(LexProblem {
            line,
            column,
            message,
        })
    };
    let mut open: Vec<(char, usize)> = Vec::new();
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        let next = chars.get(k + 1).copied();
        match c {
            '/' if next == Some('/') => {
                while k < chars.len() && chars[k] != '\n' {
                    k += 1;
                }
                continue;
            }
            '/' if next == Some('*') => {
                let start = k;
                let mut depth = 0usize;
                loop {
                    match (chars.get(k), chars.get(k + 1)) {
                        (None, _) => {
                            return at(
                                start,
                                "unterminated comment: this `/*` is never closed by `*/`".into(),
                            )
                        }
                        (Some('/'), Some('*')) => {
                            depth += 1;
                            k += 2;
                        }
                        (Some('*'), Some('/')) => {
                            depth -= 1;
                            k += 2;
                            if depth == 0 {
                                break;
                            }
                        }
                        _ => k += 1,
                    }
                }
                continue;
            }
            '"' => {
                let start = k;
                k += 1;
                while k < chars.len() && chars[k] != '"' {
                    k += 1 + usize::from(chars[k] == '\\');
                }
                if k >= chars.len() {
                    return at(
                        start,
                        "unterminated string: this `\"` is never closed".into(),
                    );
                }
            }
            '(' | '[' | '{' => open.push((c, k)),
            ')' | ']' | '}' => match open.pop() {
                None => return at(k, format!("`{c}` closes nothing: no bracket is open here")),
                Some((opener, start)) if closer(opener) != c => {
                    let (line, column) = places[k];
                    return at(
                        start,
                        format!(
                            "this `{opener}` is never closed: the `{c}` at line {line}, column \
                             {column} comes before its `{}`",
                            closer(opener)
                        ),
                    );
                }
                Some(_) => {}
            },
            '#' if !rust && !matches!(next, Some('[') | Some('!')) => {
                return at(
                    k,
                    "`#` does not start a comment in the DSL: write `// ..` (or `/// ..` for \
                     documentation)"
                        .into(),
                );
            }
            '\'' if !rust => {
                return at(
                    k,
                    "`'` is not part of the DSL: a derivative is written `der(x)`".into(),
                );
            }
            c if !c.is_ascii() && !c.is_alphabetic() && !c.is_whitespace() => {
                let hint = match c {
                    '²' | '³' | '¹' | '⁰'..='⁹' => ": write a power as `x^2`",
                    '·' | '×' | '⋅' => ": write a product as `a*b`",
                    '−' | '–' => ": write a minus as `-`",
                    _ => "",
                };
                return at(k, format!("`{c}` is not a character of the DSL{hint}"));
            }
            _ => {}
        }
        k += 1;
    }
    let (opener, start) = open.pop()?;
    at(
        start,
        format!(
            "this `{opener}` is never closed: the text ends before its `{}`",
            closer(opener)
        ),
    )
}

fn closer(opener: char) -> char {
    match opener {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}
