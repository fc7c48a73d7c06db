//! The scene's domain: settings read from TOML, their defaults, their one validation, the
//! completed start, and the allowed modes enforced by the run.

use equations::layout::{V_X, V_Y};
use equations::{
    simulate, AllowedModes, DiskConfig, DiskRecorder, ErrorNorm, GeneratedModels, InitialState,
    Integrator, InteriorChecks, Mode, RunTable, SceneSettings, SlipSign, SolverTable, StepControl,
    StopReason, TimeVariable,
};

/// The paper's scene without a `[solver]` table.
const PAPER: &str = r#"
[disk]
m = 0.4387
a = 0.03755
g = 9.81
[friction]
mu_d = 0.115
mu_st = 0.2
[initial]
theta = 0.5707963267948966
Omega_x = 1.0
[run]
t_end = 0.2
"#;

fn settings(text: &str) -> SceneSettings {
    toml::from_str(text).unwrap_or_else(|e| panic!("{e}"))
}

fn keys(s: &SceneSettings) -> Vec<String> {
    s.resolve()
        .expect_err("should be rejected")
        .into_iter()
        .map(|i| i.key)
        .collect()
}

#[test]
fn a_scene_round_trips_through_toml() {
    let full = format!(
        "{PAPER}[air]\nmu_a = 0.1\nw_z = -0.5\n[modes]\nallowed = [\"sliding\"]\n\
         [solver]\nintegrator = \"rodas4\"\nrtol = 1e-9\natol = 1e-11\n\
         guard_checks = \"exact:4\"\nerror_norm = \"vectors\"\nstep_control = \"pi-hairer\"\n\
         time = \"physical\"\n"
    );
    let s = settings(&full);
    assert_eq!(s.solver.integrator, Integrator::Rodas4);
    assert_eq!(s.solver.guard_checks, InteriorChecks::Exact(4));
    assert_eq!(s.solver.error_norm, ErrorNorm::Vectors);
    assert_eq!(s.solver.step_control, StepControl::PiHairer);
    assert_eq!(s.solver.time, TimeVariable::Physical);
    assert_eq!(s.modes.allowed, [Mode::Sliding]);
    assert_eq!(s.air.w_z, -0.5);
    let text = toml::to_string(&s).unwrap();
    assert!(text.contains("guard_checks = \"exact:4\""), "{text}");
    assert!(text.contains("integrator = \"rodas4\""), "{text}");
    assert_eq!(settings(&text), s);
}

#[test]
fn a_scene_without_solver_gets_the_documented_defaults() {
    let s = settings(PAPER);
    assert_eq!(s.solver, SolverTable::default());
    // The documented values (SolverTable's docs, README), spelled out.
    let d = &s.solver;
    assert_eq!(d.integrator, Integrator::Dop853);
    assert_eq!((d.rtol, d.atol), (1e-8, 1e-10));
    assert_eq!(d.guard_checks, InteriorChecks::Screened(64));
    assert_eq!(d.error_norm, ErrorNorm::Components);
    assert_eq!(d.step_control, StepControl::PiGustafsson);
    assert_eq!(d.time, TimeVariable::Regularised);
    assert_eq!(s.run.sample_rate, RunTable::DEFAULT_SAMPLE_RATE);
    assert_eq!(s.run.slip_sign, SlipSign::Physical);
    assert_eq!(s.modes.allowed, [Mode::Rolling, Mode::Sliding]);
    // The library's default configuration is the same settings.
    let scene = s.resolve().unwrap();
    let expected = DiskConfig {
        t_end: 0.2,
        sample_rate: Some(1000.0),
        ..DiskConfig::default()
    };
    assert_eq!(scene.config, expected);
    assert_eq!(scene.config.stick_threshold, 1e-9);
    assert_eq!(scene.config.allowed, AllowedModes::ALL);
    // The paper's variant differs in the integrator and the time variable only.
    let paper = DiskConfig::paper();
    assert_eq!(paper.integrator, Integrator::Dopri5);
    assert_eq!(paper.time, TimeVariable::Physical);
    assert_eq!(
        DiskConfig {
            integrator: Integrator::Dop853,
            time: TimeVariable::Regularised,
            ..paper
        },
        DiskConfig::default()
    );
}

#[test]
fn the_stick_threshold_follows_atol() {
    let s = settings(&format!("{PAPER}[solver]\natol = 1e-8\n"));
    assert_eq!(s.resolve().unwrap().config.stick_threshold, 1e-7);
}

#[test]
fn every_broken_rule_is_reported_with_its_key() {
    let text = r#"
[disk]
m = -1.0
a = 0.0
g = nan
[friction]
mu_d = 0.3
mu_st = 0.2
[air]
mu_a = -1.0
w_z = inf
[initial]
Omega_x = 1.0
[modes]
allowed = ["rolling", "rolling"]
[solver]
rtol = 1e-20
atol = 2.0
[run]
t_end = -1.0
sample_rate = 0.0
"#;
    assert_eq!(
        keys(&settings(text)),
        [
            "disk.m",
            "disk.a",
            "disk.g",
            "friction.mu_st",
            "air.mu_a",
            "air.w_z",
            "solver.rtol",
            "solver.atol",
            "run.t_end",
            "run.sample_rate",
            "modes.allowed",
        ]
    );
    // With a usable radius the initial state is checked too, and modes.allowed = [] is empty.
    let text = PAPER.replace("theta = 0.5707963267948966", "theta = 4.0\nZ = 1.0")
        + "[modes]\nallowed = []\n";
    assert_eq!(keys(&settings(&text)), ["modes.allowed", "initial.theta"]);
    // A slipping start needs sliding.
    let text = PAPER.replace("Omega_x = 1.0", "v_C = 0.1\nalpha = 1.0")
        + "[modes]\nallowed = [\"rolling\"]\n";
    let issues = settings(&text).resolve().unwrap_err();
    assert_eq!(issues[0].key, "initial.v_C");
    assert!(issues[0].to_string().contains("`sliding`"), "{}", issues[0]);
    // Too many recorded samples blame the key that left its default.
    let text = PAPER.replace("t_end = 0.2", "t_end = 1e4\nsample_rate = 1000.0");
    assert_eq!(keys(&settings(&text)), ["run.t_end"]);
    let text = PAPER.replace("t_end = 0.2", "t_end = 100.0\nsample_rate = 1e5");
    assert_eq!(keys(&settings(&text)), ["run.sample_rate"]);
}

#[test]
fn simulate_applies_the_same_rules_as_a_scene() {
    let scene = settings(PAPER).resolve().unwrap();
    let models = GeneratedModels::generated(scene.params, scene.config.chart()).unwrap();
    let bad = DiskConfig {
        rtol: 1e-20,
        ..scene.config
    };
    let from_code = match simulate(&models, &bad, &scene.initial, &mut ()).map_err(|f| f.error) {
        Err(equations::SimError::Invalid { issues }) => issues,
        other => panic!("{other:?}"),
    };
    let from_scene = settings(&format!("{PAPER}[solver]\nrtol = 1e-20\n"))
        .resolve()
        .unwrap_err();
    assert_eq!(from_code, from_scene);
    // The paper's signed slip needs the polar chart the scene derives from it.
    let paper_sign = DiskConfig {
        slip_sign: SlipSign::Paper,
        ..scene.config
    };
    let err = simulate(&models, &paper_sign, &scene.initial, &mut ()).unwrap_err();
    assert!(err.to_string().contains("run.slip_sign"), "{err}");
}

#[test]
fn the_slip_given_either_way_starts_the_same_run() {
    let by_slip =
        settings(&PAPER.replace("Omega_x = 1.0", "Omega_x = 1.0\nv_C = 0.05\nalpha = 0.3"))
            .resolve()
            .unwrap();
    let start = by_slip.initial;
    assert_eq!(start.mode, Mode::Sliding);
    let by_velocity = settings(&PAPER.replace(
        "Omega_x = 1.0",
        &format!(
            "Omega_x = 1.0\nV_X = {:e}\nV_Y = {:e}",
            start.state.y[V_X], start.state.y[V_Y]
        ),
    ))
    .resolve()
    .unwrap();
    assert_eq!(by_velocity.initial.mode, Mode::Sliding);
    assert!((by_velocity.initial.state.slip.speed - 0.05).abs() < 1e-15);
    assert!((by_velocity.initial.state.slip.direction - 0.3).abs() < 1e-12);
    // The explicit start reads back through the modes' own velocity map.
    let u = start.state.velocity_slip(&by_slip.params);
    let expected = start.state.slip.vector();
    assert!((u[0] - expected[0]).abs() < 1e-16 && (u[1] - expected[1]).abs() < 1e-16);
    // Both runs take the same first decisions.
    let models = GeneratedModels::generated(by_slip.params, by_slip.config.chart()).unwrap();
    let config = DiskConfig {
        t_end: 0.02,
        sample_rate: None,
        ..by_slip.config
    };
    let run = |initial: &InitialState| {
        let mut record = DiskRecorder::default();
        let out = simulate(&models, &config, initial, &mut record).unwrap();
        (out.last.state.y, record.transitions.len())
    };
    let (a, na) = run(&by_slip.initial);
    let (b, nb) = run(&by_velocity.initial);
    assert_eq!(na, nb);
    for i in 0..a.len() {
        assert!(
            (a[i] - b[i]).abs() < 1e-9 * (1.0 + a[i].abs()),
            "component {i}"
        );
    }
}

/// Runs the paper's scene (0.2 s) with only `allowed`.
fn paper_with(allowed: &str) -> (StopReason, DiskRecorder) {
    let text = format!("{PAPER}[modes]\nallowed = {allowed}\n");
    let scene = settings(&text).resolve().unwrap();
    let models = GeneratedModels::generated(scene.params, scene.config.chart()).unwrap();
    let mut record = DiskRecorder::default();
    let out = simulate(&models, &scene.config, &scene.initial, &mut record).unwrap();
    (out.stop, record)
}

#[test]
fn a_forbidden_mode_stops_the_run_with_its_own_reason() {
    // Sliding only: the disk first sticks at t ≈ 0.0722 s, where the run ends.
    let (stop, record) = paper_with("[\"sliding\"]");
    let StopReason::ModeNotAllowed { t, mode } = stop else {
        panic!("{stop:?}");
    };
    assert_eq!(mode, Mode::Rolling);
    assert!((t - 0.0722).abs() < 1e-4, "{t}");
    assert_eq!(record.transitions.last().unwrap().to, Mode::Rolling);
    assert_eq!(stop.name(), "mode not allowed");
    // Rolling only: the start already needs sliding (the initial friction decision).
    let (stop, _) = paper_with("[\"rolling\"]");
    assert_eq!(
        stop,
        StopReason::ModeNotAllowed {
            t: 0.0,
            mode: Mode::Sliding
        }
    );
    // Both: the run reaches its end.
    let (stop, _) = paper_with("[\"rolling\", \"sliding\"]");
    assert_eq!(stop, StopReason::EndTime);
}
