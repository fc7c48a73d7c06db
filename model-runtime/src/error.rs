//! Typed failures of an integration.
//!
//! Every way a run can fail carries the numbers that explain it (the time, the step size, the
//! component that would not converge), so a caller can report the problem in the model's terms
//! instead of reading a log. Nothing here panics and no failure is reported as a NaN state.
//!
//! A leaf of the crate: every other module reports through these types, and they depend on
//! nothing else in it (a model's own failure, [`EvalError`], lives here for that reason).

use crate::name::Name;
use crate::readable::Readable;
use std::fmt;

/// Why a model could not be evaluated at a state.
#[derive(Clone, Debug, PartialEq)]
pub enum EvalError {
    /// A pivot of the solve is zero, not finite, or cancelled to round-off at this state: the
    /// implicit system is singular here (for the disk: `sin(theta)` at a flat disk, or the
    /// sliding determinant).
    SingularPivot {
        /// The model's name.
        model: Name,
        /// The pivot as the user wrote it, e.g. `sin(theta)`.
        pivot: Name,
        /// Its value at the state (zero, infinite, NaN, or a remainder of cancellation small
        /// against the terms it was summed from).
        value: f64,
    },
    /// A computed quantity is not finite (overflow, or a non-finite input).
    NonFinite {
        /// The model's name.
        model: Name,
        /// The quantity's name (a state derivative as `der(x)`, or an output).
        quantity: Name,
        /// Its value.
        value: f64,
    },
    /// The state an event's reset assigns is not finite.
    ResetNotFinite {
        /// The event, as `mode.event`.
        event: String,
        /// The state component that is not finite.
        component: usize,
        /// Its value.
        value: f64,
    },
    /// An event that decides where the run goes ([`crate::EventAction::Decide`]) named no mode
    /// it may continue in.
    Undecided {
        /// The event, as `mode.event`.
        event: String,
        /// The mode index the decision named (`None`: it named none, or the model does not
        /// decide this event).
        mode: Option<usize>,
    },
}

impl EvalError {
    /// A compiled model's singular pivot: its names are `static`.
    #[cold]
    pub fn singular(model: &'static str, pivot: &'static str, value: f64) -> Self {
        EvalError::SingularPivot {
            model: Name::Borrowed(model),
            pivot: Name::Borrowed(pivot),
            value,
        }
    }

    /// A compiled model's non-finite quantity: its names are `static`.
    #[cold]
    pub fn non_finite(model: &'static str, quantity: &'static str, value: f64) -> Self {
        EvalError::NonFinite {
            model: Name::Borrowed(model),
            quantity: Name::Borrowed(quantity),
            value,
        }
    }
}

impl fmt::Display for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EvalError::SingularPivot {
                model,
                pivot,
                value,
            } => write!(
                f,
                "model `{model}` is singular here: pivot `{pivot}` = {value}",
                value = Readable(*value)
            ),
            EvalError::NonFinite {
                model,
                quantity,
                value,
            } => write!(f, "model `{model}`: `{quantity}` is not finite ({value})"),
            EvalError::ResetNotFinite {
                event,
                component,
                value,
            } => write!(
                f,
                "the reset of event `{event}` assigns state component {component} = {value}"
            ),
            EvalError::Undecided {
                event,
                mode: Some(mode),
            } => write!(
                f,
                "event `{event}` decided to go on in mode {mode}, which it does not list"
            ),
            EvalError::Undecided { event, mode: None } => write!(
                f,
                "event `{event}` decided nothing: it names no mode to go on in, and may not stop"
            ),
        }
    }
}

impl std::error::Error for EvalError {}

/// Why a single-mode integration (or one segment of a hybrid run) failed.
#[derive(Clone, Debug, PartialEq)]
pub enum SolveError {
    /// The step size fell below the smallest usable step while the local error stayed too large:
    /// the solution is (nearly) singular here, or the tolerances are unreachable.
    StepSizeCollapse {
        /// Time at which the step was attempted.
        t: f64,
        /// The step size that was still rejected.
        h: f64,
        /// The smallest step the solver may take at `t`.
        h_min: f64,
        /// Index of the state component with the largest scaled error in the last attempt.
        component: usize,
        /// The scaled error norm of the last attempt (`> 1` means rejected; may be infinite).
        error_norm: f64,
    },
    /// The model could not be evaluated.
    Eval {
        /// Time of the failed evaluation.
        t: f64,
        /// The model's own explanation.
        source: EvalError,
    },
    /// The step budget was exhausted before the end time.
    MaxSteps {
        /// Time reached.
        t: f64,
        /// The budget (accepted plus rejected steps).
        steps: u64,
    },
    /// The implicit method's iteration matrix `I/(h*gamma) - J` stayed singular while the
    /// step shrank to its minimum.
    SingularIterationMatrix {
        /// Time of the step.
        t: f64,
        /// The last step size tried.
        h: f64,
    },
    /// A guard function returned a value that is not finite.
    GuardNotFinite {
        /// Time of the evaluation.
        t: f64,
        /// Index of the guard in its mode's guard list.
        guard: usize,
        /// The value returned.
        value: f64,
    },
    /// A guard of the current mode was found on the side where it holds without having fired
    /// (and without one of the exceptions [`crate::GuardSpec`] names): the driver's invariant,
    /// violated. The run ends here rather than go on past a crossing it did not locate.
    GuardHolds {
        /// The end of the step where it was found.
        t: f64,
        /// Index of the guard in its mode's guard list.
        guard: usize,
        /// Its value there.
        value: f64,
    },
    /// A transition map returned a state with a component that is not finite.
    TransitionState {
        /// The event time.
        t: f64,
        /// The offending component.
        component: usize,
        /// Its value.
        value: f64,
    },
    /// The problem was set up inconsistently.
    InvalidInput(InputError),
}

impl SolveError {
    /// When the failure happened; an input error has no time.
    pub fn time(&self) -> Option<f64> {
        match self {
            SolveError::StepSizeCollapse { t, .. }
            | SolveError::Eval { t, .. }
            | SolveError::MaxSteps { t, .. }
            | SolveError::SingularIterationMatrix { t, .. }
            | SolveError::GuardNotFinite { t, .. }
            | SolveError::GuardHolds { t, .. }
            | SolveError::TransitionState { t, .. } => Some(*t),
            SolveError::InvalidInput(_) => None,
        }
    }

    /// The same failure dated `t` instead (a run in regularised time reports the physical
    /// time, not the integration variable's); an input error has no time and is unchanged.
    pub fn at_time(mut self, t_new: f64) -> Self {
        match &mut self {
            SolveError::StepSizeCollapse { t, .. }
            | SolveError::Eval { t, .. }
            | SolveError::MaxSteps { t, .. }
            | SolveError::SingularIterationMatrix { t, .. }
            | SolveError::GuardNotFinite { t, .. }
            | SolveError::GuardHolds { t, .. }
            | SolveError::TransitionState { t, .. } => *t = t_new,
            SolveError::InvalidInput(_) => {}
        }
        self
    }
}

/// A problem with the arguments of a run, found before any step is taken.
#[derive(Clone, Debug, PartialEq)]
pub enum InputError {
    /// A tolerance is negative or not finite, or both are zero for a component.
    Tolerance {
        /// The offending component.
        component: usize,
        /// Its relative tolerance.
        rtol: f64,
        /// Its absolute tolerance.
        atol: f64,
    },
    /// A vector has another number of components than the model has states (possible only
    /// for a size known at run time, [`crate::Dyn`]).
    Size {
        /// What the vector is (`"atol"`, `"initial state"`, ...).
        what: &'static str,
        /// The model's number of states.
        expected: usize,
        /// The vector's number of components.
        found: usize,
    },
    /// A group of components declared as one vector for the error norm is unusable.
    ComponentGroup {
        /// The group's position in the declared list.
        group: usize,
        /// Its first component.
        start: usize,
        /// One past its last component.
        end: usize,
        /// What is wrong with it.
        problem: GroupProblem,
    },
    /// An initial state component is not finite.
    InitialState {
        /// The offending component.
        component: usize,
        /// Its value.
        value: f64,
    },
    /// A time of the span is not finite (or, for a driver that runs forward only, the end
    /// is before the start).
    TimeSpan {
        /// Start time.
        t0: f64,
        /// End time.
        t_end: f64,
    },
    /// The end time is before the start time, for a run that goes forward only: a switched
    /// model's ([`crate::run_switched`]), whose resets map the state before an event to the
    /// state after it.
    ForwardOnly {
        /// Start time.
        t0: f64,
        /// End time.
        t_end: f64,
    },
    /// A fixed or initial step size is not positive and finite.
    StepSize {
        /// The step size given.
        h: f64,
    },
    /// A sampling rate is not positive and finite.
    SampleRate {
        /// The rate given (samples per unit time).
        rate: f64,
    },
    /// A chattering limit is unusable (zero transitions or a non-positive window).
    ChatterLimit {
        /// Transitions allowed within the window.
        max_transitions: usize,
        /// The window's width.
        window: f64,
    },
    /// A number of an accumulation rule is unusable.
    AccumulationRule {
        /// The field, e.g. `tail`.
        field: &'static str,
        /// Its value.
        value: f64,
    },
}

/// Why a component group cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroupProblem {
    /// It has no component.
    Empty,
    /// It reaches past the last state component.
    OutOfRange {
        /// The number of state components.
        dim: usize,
    },
    /// It shares a component with an earlier group.
    Overlaps {
        /// The earlier group's position in the declared list.
        other: usize,
    },
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::StepSizeCollapse {
                t,
                h,
                h_min,
                component,
                error_norm,
            } => write!(
                f,
                "step size collapsed at t = {t}: h = {h} (minimum {h_min}), \
                 largest error in component {component} (scaled error {error_norm})",
                h = Readable(*h),
                h_min = Readable(*h_min),
                error_norm = Readable(*error_norm)
            ),
            SolveError::Eval { t, source } => write!(f, "at t = {t}: {source}"),
            SolveError::MaxSteps { t, steps } => {
                write!(f, "gave up at t = {t} after {steps} steps")
            }
            SolveError::SingularIterationMatrix { t, h } => write!(
                f,
                "iteration matrix singular at t = {t} even with step size {h}",
                h = Readable(*h)
            ),
            SolveError::GuardNotFinite { t, guard, value } => {
                write!(f, "guard {guard} is not finite at t = {t}: {value}")
            }
            SolveError::GuardHolds { t, guard, value } => write!(
                f,
                "guard {guard} holds at t = {t} (value {value}) without having fired: a crossing \
                 was not located"
            ),
            SolveError::TransitionState {
                t,
                component,
                value,
            } => write!(
                f,
                "the transition at t = {t} returned state component {component} = {value}"
            ),
            SolveError::InvalidInput(e) => write!(f, "invalid input: {e}"),
        }
    }
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputError::Tolerance {
                component,
                rtol,
                atol,
            } => write!(
                f,
                "tolerance of component {component} unusable (rtol = {rtol}, atol = {atol})",
                rtol = Readable(*rtol),
                atol = Readable(*atol)
            ),
            InputError::Size {
                what,
                expected,
                found,
            } => write!(
                f,
                "the {what} has {found} components, the model {expected} states"
            ),
            InputError::ComponentGroup {
                group,
                start,
                end,
                problem,
            } => {
                write!(f, "component group {group} (components {start}..{end}) ")?;
                match problem {
                    GroupProblem::Empty => write!(f, "is empty"),
                    GroupProblem::OutOfRange { dim } => {
                        write!(f, "reaches past the {dim} state components")
                    }
                    GroupProblem::Overlaps { other } => write!(f, "overlaps group {other}"),
                }
            }
            InputError::InitialState { component, value } => {
                write!(f, "initial state component {component} is {value}")
            }
            InputError::TimeSpan { t0, t_end } => {
                write!(f, "time span [{t0}, {t_end}] is empty or not finite")
            }
            InputError::ForwardOnly { t0, t_end } => write!(
                f,
                "t_end = {t_end} is before t0 = {t0}: a switched model runs forward in time \
                 only (its resets give the state after an event from the state before it, and \
                 going back would need their inverses)"
            ),
            InputError::StepSize { h } => write!(f, "step size {h} is not positive and finite"),
            InputError::SampleRate { rate } => {
                write!(f, "sample rate {rate} is not positive and finite")
            }
            InputError::ChatterLimit {
                max_transitions,
                window,
            } => write!(
                f,
                "chattering limit of {max_transitions} transitions in {window} is unusable"
            ),
            InputError::AccumulationRule { field, value } => {
                write!(f, "accumulation rule: `{field}` = {value} is unusable")
            }
        }
    }
}

impl std::error::Error for SolveError {}
impl std::error::Error for InputError {}

impl From<InputError> for SolveError {
    fn from(e: InputError) -> Self {
        SolveError::InvalidInput(e)
    }
}

/// Attaches the time of the failed evaluation to a model error.
pub(crate) fn at(t: f64) -> impl Fn(EvalError) -> SolveError {
    move |source| SolveError::Eval { t, source }
}

/// A setting written as a word (in a scene file or on a command line) that is not one of its
/// spellings: which setting, what was written, and what it may be.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseSettingError {
    /// The setting, e.g. `step control`.
    pub setting: &'static str,
    /// What was written.
    pub text: String,
    /// The valid spellings, e.g. `integral, pi-hairer or pi-gustafsson`.
    pub expected: &'static str,
}

impl fmt::Display for ParseSettingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {:?}: expected {}",
            self.setting, self.text, self.expected
        )
    }
}

impl std::error::Error for ParseSettingError {}

/// The value of `choices` whose `Display` spelling is `text`: the reading of a setting spelled
/// as one word per value (`expected` lists them for the error).
pub fn parse_word<T: Copy + fmt::Display>(
    text: &str,
    choices: &[T],
    setting: &'static str,
    expected: &'static str,
) -> Result<T, ParseSettingError> {
    choices
        .iter()
        .copied()
        .find(|c| c.to_string() == text)
        .ok_or_else(|| ParseSettingError {
            setting,
            text: text.to_owned(),
            expected,
        })
}
