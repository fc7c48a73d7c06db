//! A target whose input is text made by the shared mutations ([`crate::mutate`]): its name,
//! its seeds, its words and its check are all that differ between the DSL, scene and sweep
//! targets.

use crate::mutate::{mutated, Vocabulary};
use crate::rng::Rng;
use crate::supervisor::{Corpus, Target};

/// A text target.
#[derive(Debug)]
pub struct TextTarget {
    name: &'static str,
    extension: &'static str,
    corpus: Corpus,
    vocabulary: &'static Vocabulary,
    check: fn(&str) -> Result<(), String>,
}

impl TextTarget {
    /// The target `name` whose inputs (saved as `.extension`) are mutations of the files in
    /// `dirs` with `vocabulary`, each checked by `check`.
    pub const fn new(
        name: &'static str,
        extension: &'static str,
        dirs: &'static [&'static str],
        vocabulary: &'static Vocabulary,
        check: fn(&str) -> Result<(), String>,
    ) -> TextTarget {
        TextTarget {
            name,
            extension,
            corpus: Corpus::new(dirs),
            vocabulary,
            check,
        }
    }
}

impl Target for TextTarget {
    fn name(&self) -> &'static str {
        self.name
    }

    fn extension(&self) -> &'static str {
        self.extension
    }

    fn seeds(&self) -> &[String] {
        self.corpus.texts()
    }

    fn input(&self, rng: &mut Rng) -> String {
        mutated(rng, self.corpus.texts(), self.vocabulary)
    }

    fn check(&self, input: &str) -> Result<(), String> {
        (self.check)(input)
    }
}
