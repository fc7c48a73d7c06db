//! Random hybrid models, each both as model-language text and as plain numbers that the
//! reference driver evaluates without the language's compiler: one to three modes of a forced,
//! damped oscillator (`der(x) = v`, `der(v) = a x + b v + c + d sin(t)`), whose events guard a
//! state, the time, a `let` or an output, and reset, switch, stop or accumulate.

/// A small deterministic generator (SplitMix64): the same seed gives the same model on
/// every machine, without a dependency.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// The generator seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`, rounded to three decimals (so that the text is the number).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        ((lo + (hi - lo) * u) * 1000.0).round() / 1000.0
    }

    /// Uniform in `0..n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.range(0.0, 1.0) < p
    }
}

/// What a guard compares with its threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Quantity {
    /// The state `x`.
    X,
    /// The state `v`.
    V,
    /// The time.
    T,
    /// `let q = x + K v`.
    Let,
    /// `outputs { o = x + P v^2 }`.
    Output,
}

/// How: `<` (fires downwards), `>` (upwards), `==` (either way).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Relation {
    /// `<`.
    Less,
    /// `>`.
    Greater,
    /// `==`.
    Equal,
}

/// What a reset assigns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reset {
    /// Nothing.
    None,
    /// `v = -e v`.
    Bounce(f64),
    /// `x = c`.
    SetX(f64),
}

/// What an event does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Resets, then goes on in `to` (`None`: its own mode, a restart).
    Go { to: Option<usize>, reset: Reset },
    /// Ends the run.
    Stop,
}

/// One event of a mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    /// Its name, unique in the model.
    pub name: String,
    /// The guard: `quantity relation threshold`.
    pub quantity: Quantity,
    /// The relation.
    pub relation: Relation,
    /// The threshold.
    pub threshold: f64,
    /// What it does.
    pub action: Action,
    /// `accumulates -> mode { v = 0; }`, for a restart.
    pub accumulates: Option<usize>,
}

/// One mode: its dynamics' coefficients and its events.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// `der(v) = a x + b v + c + d sin(t)`.
    pub a: f64,
    /// Damping.
    pub b: f64,
    /// Constant force.
    pub c: f64,
    /// Forcing.
    pub d: f64,
    /// Its events, in priority order.
    pub events: Vec<Event>,
}

/// A random model.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// The seed it was made from.
    pub seed: u64,
    /// `let q = x + k v`.
    pub k: f64,
    /// `o = x + p v^2`.
    pub p: f64,
    /// The initial state.
    pub x0: f64,
    /// The initial velocity.
    pub v0: f64,
    /// The modes; the run starts in the first.
    pub modes: Vec<Mode>,
}

impl Model {
    /// The model of `seed`.
    pub fn random(seed: u64) -> Self {
        let mut rng = Rng::new(seed);
        let n_modes = 1 + rng.below(3);
        let modes = (0..n_modes)
            .map(|m| {
                let n_events = 1 + rng.below(2);
                Mode {
                    a: rng.range(-30.0, 2.0),
                    b: rng.range(-1.0, 0.2),
                    c: rng.range(-10.0, 10.0),
                    d: if rng.chance(0.3) {
                        rng.range(-5.0, 5.0)
                    } else {
                        0.0
                    },
                    events: (0..n_events)
                        .map(|e| random_event(&mut rng, m, e, n_modes))
                        .collect(),
                }
            })
            .collect();
        Model {
            seed,
            k: rng.range(-0.5, 0.5),
            p: rng.range(-0.2, 0.2),
            x0: rng.range(-1.0, 1.0),
            v0: rng.range(-2.0, 2.0),
            modes,
        }
    }

    /// The model in the model language.
    pub fn text(&self) -> String {
        self.text_named("rnd")
    }

    /// The model in the model language, as module `name`.
    pub fn text_named(&self, name: &str) -> String {
        let mut s = format!(
            "mod {name} {{\n    states {{ x = {}, v = {} }}\n    let q = x + {} * v;\n    \
             outputs {{ o = x + {} * v^2; }}\n",
            num(self.x0),
            num(self.v0),
            num(self.k),
            num(self.p)
        );
        for (m, mode) in self.modes.iter().enumerate() {
            s += &format!(
                "    mode m{m} {{\n        equations {{ der(x) = v; der(v) = {} * x + {} * v + {} + {} * sin(t); }}\n",
                num(mode.a),
                num(mode.b),
                num(mode.c),
                num(mode.d)
            );
            for e in &mode.events {
                s += &format!("        {}\n", event_text(e));
            }
            s += "    }\n";
        }
        s + "}\n"
    }
}

fn random_event(rng: &mut Rng, mode: usize, index: usize, n_modes: usize) -> Event {
    let quantity = [
        Quantity::X,
        Quantity::X,
        Quantity::V,
        Quantity::T,
        Quantity::Let,
        Quantity::Output,
    ][rng.below(6)];
    let relation = [Relation::Less, Relation::Greater, Relation::Equal][rng.below(3)];
    let threshold = match quantity {
        Quantity::T => rng.range(0.0, 2.0),
        _ => rng.range(-1.0, 1.0),
    };
    let reset = match rng.below(3) {
        0 => Reset::None,
        1 => Reset::Bounce(rng.range(0.3, 0.95)),
        _ => Reset::SetX(rng.range(-1.0, 1.0)),
    };
    let action = match rng.below(8) {
        0 => Action::Stop,
        1..=3 if n_modes > 1 => Action::Go {
            to: Some((mode + 1 + rng.below(n_modes - 1)) % n_modes),
            reset,
        },
        _ => Action::Go { to: None, reset },
    };
    // A restart changes the state (an empty reset would be a record, which passes).
    let action = match action {
        Action::Go {
            to: None,
            reset: Reset::None,
        } => Action::Go {
            to: None,
            reset: Reset::Bounce(0.8),
        },
        other => other,
    };
    let restarts = matches!(action, Action::Go { to: None, .. });
    let accumulates = (restarts && rng.chance(0.5)).then(|| rng.below(n_modes));
    Event {
        name: format!("m{mode}e{index}"),
        quantity,
        relation,
        threshold,
        action,
        accumulates,
    }
}

/// A number as an expression (negative ones in parentheses).
fn num(v: f64) -> String {
    if v < 0.0 {
        format!("({v})")
    } else {
        format!("{v}")
    }
}

fn event_text(e: &Event) -> String {
    let lhs = match e.quantity {
        Quantity::X => "x",
        Quantity::V => "v",
        Quantity::T => "t",
        Quantity::Let => "q",
        Quantity::Output => "o",
    };
    let op = match e.relation {
        Relation::Less => "<",
        Relation::Greater => ">",
        Relation::Equal => "==",
    };
    let guard = format!("when {}: {lhs} {op} {}", e.name, num(e.threshold));
    let mut s = match e.action {
        Action::Stop => format!("{guard} -> stop;"),
        Action::Go { to, reset } => {
            let target = to.map(|m| format!(" -> m{m}")).unwrap_or_default();
            let body = match reset {
                Reset::None => String::new(),
                Reset::Bounce(e) => format!(" {{ v = {} * v; }}", num(-e)),
                Reset::SetX(c) => format!(" {{ x = {}; }}", num(c)),
            };
            let end = if body.is_empty() { ";" } else { "" };
            format!("{guard}{target}{body}{end}")
        }
    };
    if let Some(m) = e.accumulates {
        s += &format!("\n        when {} accumulates -> m{m} {{ v = 0; }}", e.name);
    }
    s
}
