//! Why a model file cannot be loaded, a value cannot be set, a request cannot be run or a run
//! failed: one enum per stage, so a front end says each in its own words (a command line
//! names its flags, a Python package its keyword arguments) without reading a message.

use crate::solution::Solution;
use model_algebra::EvalFailure;
use model_dsl::LocatedErrors;
use model_runtime::WorkExceeded;
use std::path::PathBuf;

/// Why a model file could not be loaded or a model chosen from it.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The model has errors (each located in the text).
    #[error("{0}")]
    Dsl(LocatedErrors),
    /// The chart asked for is not one of the file's models.
    #[error("`{name}` is not a chart of the model; the file defines {available}")]
    NoSuchChart {
        /// The name asked for.
        name: String,
        /// The models the file defines, quoted.
        available: String,
    },
    /// A switched model has no charts.
    #[error("chart `{chart}`: a switched model has no charts")]
    ChartOfSwitched {
        /// The chart asked for.
        chart: String,
    },
    /// The operation needs a smooth model (one without modes and events).
    #[error(
        "`{model}` is a switched model (it has modes or events): use `model show` or `model solve`"
    )]
    Switched {
        /// The model's name.
        model: String,
    },
}

/// Why a list of named values (parameters, initial states) cannot be applied to a model.
/// `index` is the position of the offending value in the list given, so that a front end can
/// point at the argument it came from.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ValueError {
    /// The model has no quantity of that name.
    #[error("the model has no `{name}`; the names are {names}")]
    Unknown {
        /// Position in the given list.
        index: usize,
        /// The name given.
        name: String,
        /// The model's names, quoted.
        names: String,
    },
    /// The same name is given twice.
    #[error("`{name}` is given twice")]
    Twice {
        /// Position of the second one in the given list.
        index: usize,
        /// The name.
        name: String,
    },
    /// The value is NaN or infinite.
    #[error("`{name}` = {value} is not a finite number")]
    NotFinite {
        /// Position in the given list.
        index: usize,
        /// The name.
        name: String,
        /// The value.
        value: f64,
    },
    /// A parameter without a default in the file was not given.
    #[error("parameter `{name}` has no default in the file and is not given")]
    Missing {
        /// The parameter.
        name: String,
    },
}

impl ValueError {
    /// The position of the offending value in the list given (`None`: a value is missing).
    pub fn index(&self) -> Option<usize> {
        match self {
            ValueError::Unknown { index, .. }
            | ValueError::Twice { index, .. }
            | ValueError::NotFinite { index, .. } => Some(*index),
            ValueError::Missing { .. } => None,
        }
    }
}

/// A request [`crate::solve`] cannot run, found before any integration: an input error.
#[derive(Debug, thiserror::Error)]
pub enum RequestError {
    /// A parameter value.
    #[error("parameters: {0}")]
    Params(ValueError),
    /// An initial state value.
    #[error("initial state: {0}")]
    State(ValueError),
    /// An event names nothing the model has.
    #[error("event `{name}`: {problem}", name = .0.name, problem = .0)]
    UnknownEvent(UnknownEvent),
    /// A switched model declares its events in the file; the request gave some.
    #[error(
        "event `{name}`: a switched model declares its events in the file (`when NAME: GUARD`)"
    )]
    EventsOfSwitched {
        /// The first event given.
        name: String,
    },
    /// Both a sampling step and sampling times were given.
    #[error("give a sampling step or sampling times, not both")]
    StepAndTimes,
    /// A sampling time is not finite, outside the run's span, or not after the one before in
    /// the run's direction.
    #[error("sampling time #{index} (t = {t}) {problem} (the run goes from {t0} to {t_end})")]
    Time {
        /// Its position in the list given.
        index: usize,
        /// The time.
        t: f64,
        /// What is wrong with it.
        problem: &'static str,
        /// The run's start.
        t0: f64,
        /// The run's end.
        t_end: f64,
    },
    /// A switched model records at a rate or at every step, not at given times.
    #[error("`{model}` is a switched model: it records every step or at a sampling step, not at given times")]
    TimesOfSwitched {
        /// The model.
        model: String,
    },
    /// A switched model asked to run backward in time.
    #[error(
        "`{model}` is a switched model: it runs forward in time only (t_end = {t_end} is before \
         t0 = {t0}): its events' resets give the state after an event from the state before \
         it, and going back would need their inverses, which a model file does not give (a \
         reset that loses energy has none)"
    )]
    BackwardOfSwitched {
        /// The model.
        model: String,
        /// The run's start.
        t0: f64,
        /// The run's end (before `t0`).
        t_end: f64,
    },
    /// The sampling step is not positive and finite.
    #[error("dt = {dt}: the sampling step must be positive and finite")]
    SampleStep {
        /// The step.
        dt: f64,
    },
    /// The sampling step gives no samples or too many.
    #[error("dt = {dt} from {t0} to {t_end}: gives no samples or too many (at most 1e8)")]
    SampleCount {
        /// The step.
        dt: f64,
        /// The start.
        t0: f64,
        /// The end.
        t_end: f64,
    },
    /// More sampling times than a solve records ([`crate::MAX_SAMPLES`]).
    #[error("{count} sampling times: at most {max} are recorded", max = crate::MAX_SAMPLES)]
    TimeCount {
        /// How many were given.
        count: usize,
    },
    /// The work bound is not positive and finite.
    #[error("max_steps_per_s = {steps_per_s}: the work bound must be positive and finite")]
    WorkBound {
        /// The bound given.
        steps_per_s: f64,
    },
    /// The runtime refused a setting (the time span, a tolerance), in its words.
    #[error("{0}")]
    Settings(String),
}

/// An event of a request names neither a state nor an output of the model.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "the model has no state or output `{name}`; the states are {states}; the outputs are {outputs}"
)]
pub struct UnknownEvent {
    /// Position in the request's event list.
    pub index: usize,
    /// The name given.
    pub name: String,
    /// The model's states, quoted.
    pub states: String,
    /// The model's outputs, quoted.
    pub outputs: String,
}

/// Why [`crate::solve`] gave no solution.
#[derive(Debug, thiserror::Error)]
pub enum SolveFailure {
    /// The request is unusable (an input error; nothing was integrated).
    #[error(transparent)]
    Request(#[from] RequestError),
    /// The model's modes and events do not form a valid graph.
    #[error("{0}")]
    Graph(String),
    /// The integration failed, said in the model's terms (a state, a pivot, a mode by name).
    #[error("{0}")]
    Run(RunFailure),
    /// The interpreter could not evaluate a recorded point's outputs.
    #[error("at t = {t}: {failure}")]
    Eval {
        /// The point's time.
        t: f64,
        /// Why.
        failure: PointError,
    },
}

/// A failed integration, the work done until then, and what was computed.
#[derive(Clone, Debug, PartialEq)]
pub struct RunFailure {
    /// What went wrong, in the model's terms.
    pub message: String,
    /// The steps accepted before the failure (`None`: the runtime does not say).
    pub steps: Option<u64>,
    /// The events met before the failure.
    pub events: usize,
    /// The work bound, when the run went over it ([`crate::SolveRequest::max_steps_per_s`]).
    pub work: Option<WorkExceeded>,
    /// What the run's last steps suggest when it went over its work bound.
    pub hint: Option<WorkHint>,
    /// The solution until the failure (its stop [`crate::Stop::Failed`]): the rows and
    /// events computed, for a front end to keep.
    pub partial: Option<Box<Solution>>,
}

/// Why a run that went over its work bound took such short steps, as far as its record shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WorkHint {
    /// Few events under an explicit method: a stiff model, which makes an explicit method
    /// take ever shorter steps (an implicit one is the way out).
    Stiff,
    /// At least one event per ten steps: firings coming ever faster, an accumulation.
    Events,
}

impl WorkHint {
    /// The hint for a run over its work bound after `steps` steps and `events` events under
    /// an `explicit` method or not.
    pub fn of(steps: u64, events: usize, explicit: bool) -> Option<Self> {
        if events as u64 * 10 >= steps {
            Some(WorkHint::Events)
        } else {
            explicit.then_some(WorkHint::Stiff)
        }
    }
}

impl RunFailure {
    /// The failure in words, naming the setting that raises the work bound as the caller
    /// spells it (`--max-steps-per-s`).
    pub fn describe(&self, setting: &str) -> String {
        let mut text = match &self.work {
            Some(over) => over.describe(setting, ""),
            None => self.message.clone(),
        };
        match self.hint {
            Some(WorkHint::Stiff) => text.push_str(
                "; steps this short are the mark of a stiff model under an explicit method: \
                 an implicit one (`rodas4`) takes long steps there",
            ),
            Some(WorkHint::Events) => text.push_str(
                "; events took most of the steps, ever closer together: an accumulation that \
                 no `when EVENT accumulates -> MODE` rule declared (or one whose intervals \
                 the tolerances blur: tighten rtol and atol)",
            ),
            None => {}
        }
        if let Some(steps) = self.steps {
            text.push_str(&format!(
                " (after {steps} steps and {} events)",
                self.events
            ));
        }
        text
    }
}

impl std::fmt::Display for RunFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.describe("max_steps_per_s"))
    }
}

/// An unusable setting the runtime refused (a time span, a tolerance), as a request error.
pub(crate) fn settings(message: String) -> SolveFailure {
    SolveFailure::Request(RequestError::Settings(message))
}

/// Why a model cannot be evaluated at one point.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PointError {
    /// The interpreter failed (a singular pivot; a program reading what does not exist).
    #[error("{}", describe(model, failure))]
    Interpreter {
        /// The model's name.
        model: String,
        /// The interpreter's failure.
        failure: EvalFailure,
    },
    /// A derivative or an output is NaN or infinite.
    #[error("`{model}`: {name} = {value} is not finite at this state")]
    NonFinite {
        /// The model's name.
        model: String,
        /// The quantity (`der(x)` or an output's name).
        name: String,
        /// Its value.
        value: f64,
    },
}

/// An interpreter failure in the model's terms.
fn describe(model: &str, failure: &EvalFailure) -> String {
    match failure {
        EvalFailure::SingularPivot { text, value } => format!(
            "`{model}`: the pivot `{text}` is {value} at this state: the equations cannot be solved for the derivatives here"
        ),
        EvalFailure::BadOperand(operand) => format!(
            "`{model}`: the compiled program reads {operand:?}, which does not exist (a compiler bug)"
        ),
    }
}
