//! Mutations of text, shared by every target whose input is text (the DSL, scenes, sweeps).
//!
//! A seed is split into tokens (words and numbers, runs of white space, single other
//! characters) and mutated a few times: tokens deleted, repeated, swapped, replaced by a word of
//! the target's dictionary, spliced in from another seed, a number replaced by an extreme one,
//! a stray character inserted, or a stretch wrapped in deep nesting. What differs between
//! targets is only their vocabulary ([`Vocabulary`]): the mutations know no grammar, so a new
//! target needs words, not code.

use crate::rng::Rng;

/// The words a target's mutations insert.
#[derive(Clone, Copy, Debug)]
pub struct Vocabulary {
    /// Tokens to insert or to put in place of another: the language's words and operators,
    /// and things that do not belong to it.
    pub words: &'static [&'static str],
    /// Numbers that break careless arithmetic, put in place of a number of the seed.
    pub numbers: &'static [&'static str],
    /// Openings and closings wrapped around a stretch, up to [`Vocabulary::max_depth`] deep.
    pub nests: &'static [(&'static str, &'static str)],
    /// Characters the language does not expect.
    pub strays: &'static [char],
    /// The deepest nesting a mutation makes.
    pub max_depth: usize,
}

/// Input text: a seed of `corpus` (not empty) mutated one to six times with `vocabulary`.
pub fn mutated(rng: &mut Rng, corpus: &[String], vocabulary: &Vocabulary) -> String {
    let mut tokens = split(rng.pick(corpus).as_str());
    for _ in 0..1 + rng.below(6) {
        mutate(&mut tokens, rng, corpus, vocabulary);
    }
    tokens.concat()
}

fn mutate(tokens: &mut Vec<String>, rng: &mut Rng, corpus: &[String], v: &Vocabulary) {
    if tokens.is_empty() {
        tokens.push(rng.pick(v.words).to_string());
        return;
    }
    let at = rng.below(tokens.len());
    let len = 1 + rng.below(8.min(tokens.len() - at));
    match rng.below(9) {
        0 => {
            tokens.drain(at..at + len);
        }
        1 => {
            let copy: Vec<String> = tokens[at..at + len].to_vec();
            for _ in 0..1 + rng.below(4) {
                tokens.splice(at..at, copy.clone());
            }
        }
        2 => tokens.insert(at, rng.pick(v.words).to_string()),
        3 => tokens[at] = rng.pick(v.words).to_string(),
        4 => {
            let other = rng.below(tokens.len());
            tokens.swap(at, other);
        }
        5 => {
            let donor = split(rng.pick(corpus).as_str());
            let from = rng.below(donor.len().max(1));
            let to = (from + 1 + rng.below(20)).min(donor.len());
            tokens.splice(at..at, donor[from.min(to)..to].to_vec());
        }
        6 => {
            let depth = 1 + rng.below(v.max_depth);
            let (open, close) = *rng.pick(v.nests);
            tokens.insert(at, open.repeat(depth));
            tokens.insert((at + 1 + len).min(tokens.len()), close.repeat(depth));
        }
        7 => {
            let numbers: Vec<usize> = (0..tokens.len())
                .filter(|&k| tokens[k].starts_with(|c: char| c.is_ascii_digit()))
                .collect();
            if !numbers.is_empty() {
                let k = *rng.pick(&numbers);
                tokens[k] = rng.pick(v.numbers).to_string();
            }
        }
        _ => tokens.insert(at, rng.pick(v.strays).to_string()),
    }
}

/// Words (names and numbers), runs of white space and single other characters.
pub fn split(text: &str) -> Vec<String> {
    let mut tokens: Vec<String> = Vec::new();
    let class = |c: char| match c {
        c if c.is_alphanumeric() || c == '_' || c == '.' => 0,
        c if c.is_whitespace() => 1,
        _ => 2,
    };
    for c in text.chars() {
        match tokens.last_mut() {
            Some(last) if class(c) != 2 && last.chars().next().map(class) == Some(class(c)) => {
                last.push(c)
            }
            _ => tokens.push(c.to_string()),
        }
    }
    tokens
}

#[cfg(test)]
mod tests {
    use super::*;

    const WORDS: Vocabulary = Vocabulary {
        words: &["x", "+"],
        numbers: &["1e308"],
        nests: &[("(", ")")],
        strays: &['#'],
        max_depth: 50,
    };

    #[test]
    fn splitting_loses_nothing() {
        let text = "der(x) = -1.5e3 * x;\n  θ² // done";
        assert_eq!(split(text).concat(), text);
    }

    #[test]
    fn inputs_are_deterministic_and_differ() {
        let corpus = vec!["a = 1 + b(2);".to_string(), "c = 3;".to_string()];
        let make = |i| mutated(&mut Rng::for_input(7, i), &corpus, &WORDS);
        assert_eq!(make(3), make(3));
        let distinct: std::collections::BTreeSet<String> = (0..50).map(make).collect();
        assert!(distinct.len() > 25, "{distinct:?}");
    }
}
