//! Text to models: a model file (or text) read by the same front end and compiled by the same
//! equation compiler as `model!`, into a smooth model with its charts or a switched model.
//! Every mistake in the text is a located error ([`LoadError::Dsl`]), never a panic.

use crate::cache::{Key, ModelCache};
use crate::error::LoadError;
use crate::file::ModelFile;
use model_algebra::CompiledModel;
use model_dsl::{CompiledSwitched, Source};
use std::path::Path;

/// A file loaded, and what the cache of compiled models did for it.
#[derive(Debug)]
pub struct Loaded {
    /// The file's models.
    pub file: ModelFile,
    /// Whether they came from the cache.
    pub cache: CacheUse,
}

/// What the cache of compiled models did for one load.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CacheUse {
    /// No cache was given: the file was compiled.
    Off,
    /// The cache held no valid entry: the file was compiled and its entry written (or, the
    /// cache being unwritable, not).
    Miss,
    /// The compiled models were the cache's entry: nothing was compiled.
    Hit,
}

/// One model of a file, ready to evaluate or solve: a smooth model (the file's model or one
/// of its charts) or a switched one.
#[derive(Clone, Copy, Debug)]
pub enum ModelRef<'a> {
    /// A model without modes.
    Smooth(&'a CompiledModel),
    /// A model with modes and events.
    Switched(&'a CompiledSwitched),
}

impl ModelFile {
    /// Reads and compiles the file at `path`.
    pub fn read(path: &Path) -> Result<Self, LoadError> {
        Self::read_with(path, None)
    }

    /// Reads the file at `path` and compiles it, or takes its compiled models from `cache`
    /// when it holds a valid entry for this text (and keeps them there when not).
    pub fn read_with(path: &Path, cache: Option<&ModelCache>) -> Result<Self, LoadError> {
        Self::read_reporting(path, cache).map(|loaded| loaded.file)
    }

    /// [`read_with`](Self::read_with), saying whether the cache held the file.
    pub fn read_reporting(path: &Path, cache: Option<&ModelCache>) -> Result<Loaded, LoadError> {
        let source = Source::read(path).map_err(|source| LoadError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::compile_with(&source, cache)
    }

    /// Compiles `text`; `name` is the source's name in the errors' locations (a file name).
    pub fn from_text(name: &str, text: &str) -> Result<Self, LoadError> {
        Self::from_text_with(name, text, None)
    }

    /// [`from_text`](Self::from_text), through `cache` as [`read_with`](Self::read_with)
    /// (the entry is keyed by the text, whatever its name).
    pub fn from_text_with(
        name: &str,
        text: &str,
        cache: Option<&ModelCache>,
    ) -> Result<Self, LoadError> {
        Self::from_text_reporting(name, text, cache).map(|loaded| loaded.file)
    }

    /// [`from_text_with`](Self::from_text_with), saying whether the cache held the text.
    pub fn from_text_reporting(
        name: &str,
        text: &str,
        cache: Option<&ModelCache>,
    ) -> Result<Loaded, LoadError> {
        Self::compile_with(&Source::new(name, text), cache)
    }

    /// `source` compiled, or taken from `cache` (and kept there when compiled).
    fn compile_with(source: &Source, cache: Option<&ModelCache>) -> Result<Loaded, LoadError> {
        let Some(cache) = cache else {
            return Ok(Loaded {
                file: Self::compile(source)?,
                cache: CacheUse::Off,
            });
        };
        let key = Key::of(source);
        if let Some(file) = cache.get(&key) {
            return Ok(Loaded {
                file,
                cache: CacheUse::Hit,
            });
        }
        let file = Self::compile(source)?;
        cache.put(&key, &file);
        Ok(Loaded {
            file,
            cache: CacheUse::Miss,
        })
    }

    pub(crate) fn compile(source: &Source) -> Result<Self, LoadError> {
        let ast = source.parse().map_err(LoadError::Dsl)?;
        if ast.is_switched() {
            let model = source.compile_switched().map_err(LoadError::Dsl)?;
            return Ok(ModelFile::Switched(model));
        }
        source
            .compile()
            .map(ModelFile::Smooth)
            .map_err(LoadError::Dsl)
    }

    /// The model's name (the `mod` of the file).
    pub fn name(&self) -> &str {
        match self {
            ModelFile::Smooth(models) => models.first().map_or("", |m| &m.compiled.name),
            ModelFile::Switched(model) => &model.name,
        }
    }

    /// The model called `chart` (`None`: the file's model itself); a switched model has no
    /// charts.
    pub fn model(&self, chart: Option<&str>) -> Result<ModelRef<'_>, LoadError> {
        match (self, chart) {
            (ModelFile::Smooth(models), chart) => {
                select_chart(models.iter().map(|m| &m.compiled), chart).map(ModelRef::Smooth)
            }
            (ModelFile::Switched(model), None) => Ok(ModelRef::Switched(model)),
            (ModelFile::Switched(_), Some(chart)) => Err(LoadError::ChartOfSwitched {
                chart: chart.to_string(),
            }),
        }
    }

    /// The smooth model called `chart` (`None`: the file's model); a switched model is an
    /// error naming it.
    pub fn smooth(&self, chart: Option<&str>) -> Result<&CompiledModel, LoadError> {
        match self.model(chart) {
            Ok(ModelRef::Smooth(model)) => Ok(model),
            Ok(ModelRef::Switched(model)) => Err(LoadError::Switched {
                model: model.name.clone(),
            }),
            Err(LoadError::ChartOfSwitched { .. }) => Err(LoadError::Switched {
                model: self.name().to_string(),
            }),
            Err(err) => Err(err),
        }
    }
}

/// The model called `chart` among a file's compiled models, the model first and then its
/// charts (`None`: the model itself): for a front end that keeps only the compiled models
/// (a syntax tree stays on the thread that parsed it).
pub fn select_chart<'a>(
    models: impl IntoIterator<Item = &'a CompiledModel> + Clone,
    chart: Option<&str>,
) -> Result<&'a CompiledModel, LoadError> {
    let found = match chart {
        None => models.clone().into_iter().next(),
        Some(name) => models.clone().into_iter().find(|m| m.name == name),
    };
    found.ok_or_else(|| {
        let names: Vec<&str> = models.into_iter().map(|m| m.name.as_str()).collect();
        LoadError::NoSuchChart {
            name: chart.unwrap_or_default().to_string(),
            available: quoted(&names),
        }
    })
}

/// `` `a`, `b` `` (or `none`).
pub(crate) fn quoted<S: AsRef<str>>(names: &[S]) -> String {
    if names.is_empty() {
        return "none".to_string();
    }
    let quoted: Vec<String> = names.iter().map(|n| format!("`{}`", n.as_ref())).collect();
    quoted.join(", ")
}

impl ModelRef<'_> {
    /// The model's name.
    pub fn name(&self) -> &str {
        match self {
            ModelRef::Smooth(model) => &model.name,
            ModelRef::Switched(model) => &model.name,
        }
    }

    /// The state names, in order.
    pub fn states(&self) -> &[String] {
        match self {
            ModelRef::Smooth(model) => &model.states,
            ModelRef::Switched(model) => model.states(),
        }
    }

    /// The output names, in order (a switched model's modes share them).
    pub fn outputs(&self) -> &[String] {
        match self {
            ModelRef::Smooth(model) => &model.outputs,
            ModelRef::Switched(model) => &model.modes[0].model.outputs,
        }
    }

    /// The parameters with their defaults from the file, in order (`None`: no default).
    pub fn params(&self) -> &[(String, Option<f64>)] {
        match self {
            ModelRef::Smooth(model) => &model.params,
            ModelRef::Switched(model) => &model.modes[0].model.params,
        }
    }
}
