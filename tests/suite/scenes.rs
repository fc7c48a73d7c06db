//! Scene loading: every shipped scene validates, every rejection names its key, and random
//! edits never panic.

use eulerdisk::{
    load_scene, parse_scene, Override, Scene, SceneError, BUILTIN_SCENES, DEFAULT_SCENE,
    REQUIRED_KEYS,
};
use proptest::prelude::*;

const PAPER: &str = include_str!("../../scenes/tangent-toy.toml");

fn with_override(spec: &str) -> Result<Scene, SceneError> {
    parse_scene("tangent-toy", PAPER, &[Override::parse(spec)?])
}

#[test]
fn every_shipped_scene_loads_and_validates() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut on_disk: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    let mut builtin: Vec<String> = BUILTIN_SCENES.iter().map(|(n, _)| n.to_string()).collect();
    builtin.sort();
    assert_eq!(on_disk, builtin, "scenes/ and the built-in list differ");
    for name in &on_disk {
        let path = dir.join(format!("{name}.toml"));
        let s = load_scene(path.to_str().unwrap(), &[]).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(&s.name, name);
        let s2 = load_scene(name, &[]).unwrap();
        assert_eq!(s, s2);
    }
}

/// Every shipped scene, written back out from the settings it was read into, reads back into
/// the same scene: the CLI's tables and the equations crate's keep every key.
#[test]
fn every_shipped_scene_round_trips_through_its_settings() {
    for (name, text) in BUILTIN_SCENES {
        let s = parse_scene(name, text, &[]).unwrap();
        let written = toml::to_string(&s.file).unwrap();
        let again = parse_scene(name, &written, &[]).unwrap_or_else(|e| panic!("{e}\n{written}"));
        assert_eq!(again, s, "{name}:\n{written}");
        // The description and the outputs are the CLI's own; the rest the equations crate's.
        let tree: toml::Table = toml::from_str(&written).unwrap();
        assert_eq!(
            tree.contains_key("description"),
            s.file.cli.description.is_some()
        );
        assert!(tree.contains_key("output") && tree.contains_key("solver"));
    }
}

/// A scene without `[solver]` gets the equations crate's documented defaults, and a CLI-only
/// key in a disk table is still refused by name.
#[test]
fn a_scene_without_solver_takes_the_library_defaults() {
    let start = PAPER.find("[solver]").unwrap();
    let end = start + PAPER[start..].find("[run]").unwrap();
    let text = format!("{}{}", &PAPER[..start], &PAPER[end..]);
    let s = parse_scene("no-solver", &text, &[]).unwrap();
    assert_eq!(s.file.settings.solver, equations::SolverTable::default());
    assert_eq!(
        s.config,
        equations::DiskConfig {
            t_end: 100.0,
            sample_rate: Some(1000.0),
            ..equations::DiskConfig::default()
        }
    );
    let err = parse_scene(
        "t",
        &PAPER.replace("[solver]", "[solver]\nquantities = 1"),
        &[],
    )
    .unwrap_err();
    assert_eq!(err.keys(), ["solver.quantities"], "{err}");
}

#[test]
fn the_paper_scene_is_the_papers() {
    let s = load_scene(DEFAULT_SCENE, &[]).unwrap();
    assert_eq!(s.params, equations::DiskParams::paper());
    assert_eq!(s.config.rtol, 1e-8);
    assert_eq!(s.config.atol, 1e-10);
    assert_eq!(s.config.t_end, 100.0);
    // The paper's start, completed from the constraints.
    assert_eq!(s.initial, equations::InitialState::paper(&s.params));
    assert_eq!(s.initial.mode, equations::Mode::Rolling);
    assert_eq!(s.initial.state.slip.speed, 0.0);
}

fn expect_key(result: Result<Scene, SceneError>, key: &str, words: &str) {
    let err = result.expect_err("should be rejected");
    let text = err.to_string();
    assert!(
        err.keys().contains(&key),
        "{key} not in {:?}: {text}",
        err.keys()
    );
    assert!(text.contains(key), "{text}");
    assert!(text.contains(words), "`{words}` not in: {text}");
}

#[test]
fn each_rule_names_its_key() {
    expect_key(with_override("disk.m=0"), "disk.m", "must be > 0");
    expect_key(with_override("disk.a=-1"), "disk.a", "must be > 0");
    expect_key(with_override("disk.g=nan"), "disk.g", "finite");
    expect_key(
        with_override("friction.mu_st=0.1"),
        "friction.mu_st",
        "friction.mu_d",
    );
    expect_key(
        with_override("initial.theta=0"),
        "initial.theta",
        "(0, 3.14",
    );
    expect_key(
        with_override("initial.theta=3.2"),
        "initial.theta",
        "must lie in",
    );
    expect_key(
        with_override("initial.Omega_x=inf"),
        "initial.Omega_x",
        "finite",
    );
    expect_key(
        with_override("solver.rtol=1e-15"),
        "solver.rtol",
        "must lie in",
    );
    expect_key(with_override("solver.rtol=2"), "solver.rtol", "must lie in");
    expect_key(with_override("solver.atol=0"), "solver.atol", "must be > 0");
    expect_key(with_override("run.t_end=-1"), "run.t_end", "must be > 0");
    expect_key(
        with_override("run.sample_rate=1e9"),
        "run.sample_rate",
        "samples",
    );
    // A long run at the default rate blames the duration the user set, and says what to change.
    expect_key(
        with_override("run.t_end=1e12"),
        "run.t_end",
        "shorten `run.t_end` to at most 5000 s",
    );
    // t_end × rate overflows to infinity: over the sample limit too, not past its check.
    expect_key(
        with_override("run.t_end=1e306"),
        "run.t_end",
        "more than the sample limit",
    );
    // Finite, but the inertia m a² is not (the run started with V_X = inf).
    expect_key(
        with_override("disk.a=1.7976931348623157e308"),
        "disk.a",
        "the inertia `disk.m` × `disk.a`^2 or the weight moment",
    );
    // Every rule holds for each value, but the completed velocity a × Ω is infinite.
    expect_key(
        parse_scene(
            "t",
            PAPER,
            &[
                Override::parse("disk.a=1e150").unwrap(),
                Override::parse("initial.Omega_z=1e160").unwrap(),
            ],
        ),
        "initial.V_Y",
        "(their products overflow)",
    );
    expect_key(
        with_override("solver.guard_checks=\"exact:4294967295\""),
        "solver.guard_checks",
        "the guard-check limit",
    );
    expect_key(
        with_override("initial.Z=0.02"),
        "initial.Z",
        "Z = a sin(theta) by",
    );
    expect_key(
        with_override("initial.V_Z=1"),
        "initial.V_Z",
        "V_Z = a Omega_y cos(theta)",
    );
    expect_key(
        with_override("initial.v_C=1"),
        "initial.alpha",
        "required when `initial.v_C`",
    );
    expect_key(with_override("modes.allowed=[]"), "modes.allowed", "empty");
    expect_key(
        with_override("output.quantities=[\"theta\", \"tehta\"]"),
        "output.quantities",
        "tehta",
    );
    let rolling_only = Override::parse("modes.allowed=[\"rolling\"]").unwrap();
    let slipping = Override::parse("initial.V_X=0.5").unwrap();
    expect_key(
        parse_scene("t", PAPER, &[rolling_only, slipping]),
        "initial.v_C",
        "sliding",
    );
}

#[test]
fn shape_errors_name_the_key() {
    expect_key(
        with_override("friction.mu=0.1"),
        "friction.mu",
        "unknown field",
    );
    expect_key(with_override("extra.x=1"), "extra", "unknown field");
    expect_key(with_override("disk.m=\"heavy\""), "disk.m", "invalid type");
    expect_key(
        with_override("solver.integrator=euler"),
        "solver.integrator",
        "euler",
    );
    expect_key(
        with_override("solver.guard_checks=often"),
        "solver.guard_checks",
        "expected none, exact:N or screened:N",
    );
    expect_key(
        with_override("solver.error_norm=euclid"),
        "solver.error_norm",
        "expected components or vectors",
    );
    expect_key(
        with_override("solver.step_control=pid"),
        "solver.step_control",
        "expected integral, pi-hairer or pi-gustafsson",
    );
    expect_key(
        with_override("run.slip_sign=sometimes"),
        "run.slip_sign",
        "sometimes",
    );
    let without_mass = PAPER.replace("m = 0.4387", "");
    expect_key(
        parse_scene("t", &without_mass, &[]),
        "disk.m",
        "is required",
    );
    let without_run = PAPER.replace("[run]", "[runs]");
    expect_key(parse_scene("t", &without_run, &[]), "runs", "unknown field");
}

#[test]
fn all_issues_are_reported_together() {
    let overrides =
        ["disk.m=-1", "solver.rtol=0", "initial.theta=7"].map(|s| Override::parse(s).unwrap());
    let err = parse_scene("t", PAPER, &overrides).unwrap_err();
    let keys = err.keys();
    for key in ["disk.m", "solver.rtol", "initial.theta"] {
        assert!(keys.contains(&key), "{keys:?}");
    }
}

#[test]
fn overrides_replace_values_and_bad_overrides_are_named() {
    let s = with_override("friction.mu_d=0.15").unwrap();
    assert_eq!(s.params.mu_d, 0.15);
    let s = with_override("solver.integrator=dopri5").unwrap();
    assert_eq!(s.config.integrator.name(), "dopri5");
    let s = with_override("solver.integrator=rodas4").unwrap();
    assert_eq!(s.config.integrator.name(), "rodas4");
    let s = with_override("solver.guard_checks=exact:4").unwrap();
    assert_eq!(s.config.guard_checks, equations::InteriorChecks::Exact(4));
    let s = with_override("solver.error_norm=vectors").unwrap();
    assert_eq!(s.config.error_norm, equations::ErrorNorm::Vectors);
    let s = with_override("solver.step_control=integral").unwrap();
    assert_eq!(s.config.step_control, equations::StepControl::Integral);
    // The defaults are the library's.
    let s = with_override("solver.rtol=1e-8").unwrap();
    let paper = equations::DiskConfig::paper();
    assert_eq!(s.config.error_norm, paper.error_norm);
    assert_eq!(s.config.step_control, paper.step_control);
    for bad in ["mu_d=0.1", "friction.mu_d", ".x=1", "a.b.c=1"] {
        let err = Override::parse(bad).and_then(|o| parse_scene("t", PAPER, &[o]));
        assert!(err.is_err(), "{bad}");
        assert!(err
            .unwrap_err()
            .to_string()
            .contains(bad.split('=').next().unwrap()));
    }
}

#[test]
fn unknown_scene_lists_the_builtin_ones() {
    let err = load_scene("no-such-scene", &[]).unwrap_err();
    assert!(err.to_string().contains("tangent-toy"), "{err}");
}

fn toml_value() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|v| format!("{v:e}")),
        Just("nan".to_string()),
        Just("-inf".to_string()),
        Just("1e308".to_string()),
        any::<i64>().prop_map(|v| v.to_string()),
        "[a-z_]{0,8}".prop_map(|s| format!("\"{s}\"")),
        any::<bool>().prop_map(|b| b.to_string()),
        Just("[]".to_string()),
        Just("[1, \"x\"]".to_string()),
        Just("{ a = 1 }".to_string()),
    ]
}

const TABLES: &[&str] = &[
    "disk", "friction", "air", "initial", "modes", "solver", "run", "output", "other",
];
const KEYS: &[&str] = &[
    "m",
    "a",
    "g",
    "mu_d",
    "mu_st",
    "mu_a",
    "w_z",
    "theta",
    "Omega_x",
    "Z",
    "V_X",
    "v_C",
    "alpha",
    "allowed",
    "integrator",
    "rtol",
    "atol",
    "t_end",
    "sample_rate",
    "slip_sign",
    "quantities",
    "bogus",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Any edit of any key either loads a scene whose numbers are all finite, or is rejected
    /// with an error naming the edited key.
    #[test]
    fn random_edits_never_panic_and_rejections_name_the_key(
        table in prop::sample::select(TABLES),
        key in prop::sample::select(KEYS),
        value in toml_value(),
    ) {
        let spec = format!("{table}.{key}={value}");
        let o = Override::parse(&spec).unwrap();
        match parse_scene("t", PAPER, &[o]) {
            Ok(s) => {
                let p = s.params;
                for v in [p.m, p.a, p.g, p.mu_d, p.mu_st, p.mu_a, p.w_z] {
                    prop_assert!(v.is_finite());
                }
                for v in s.initial.state.y {
                    prop_assert!(v.is_finite());
                }
            }
            Err(e) => {
                let full = format!("{table}.{key}");
                let keys = e.keys();
                // Named as the key of the issue, or inside the message of a rule between two
                // keys (`friction.mu_st` must not be below `friction.mu_d`), or as the table
                // for a misplaced table; a bad radius shows in the constraints it enters.
                let text = e.to_string();
                prop_assert!(
                    keys.iter().any(|k| k.starts_with(&full) || *k == table
                        || (table == "disk" && key == "a" && k.starts_with("initial")))
                        || text.contains(&format!("`{full}`")),
                    "{spec}: {keys:?} {e}"
                );
            }
        }
    }

    /// Random bytes as a scene never panic the loader.
    #[test]
    fn random_text_never_panics(text in ".{0,200}") {
        let _ = parse_scene("t", &text, &[]);
    }
}

/// A scene repeating one entry a thousand times gets one issue per repeat, but the error lists
/// the first `MAX_LISTED_ISSUES` and counts the rest (11 M repeats printed 522 MB).
#[test]
fn a_long_list_of_issues_is_capped_and_counted() {
    let list = vec!["\"theta\""; 1000].join(", ");
    let err = with_override(&format!("output.quantities=[{list}]")).unwrap_err();
    let text = err.to_string();
    assert_eq!(err.keys().len(), 999);
    let limit = eulerdisk::MAX_LISTED_ISSUES;
    assert_eq!(text.lines().count(), 1 + limit + 1, "{text}");
    assert!(
        text.ends_with(&format!("... and {} more issues", 999 - limit)),
        "{text}"
    );
}

/// A scene missing several required keys names all of them in one error, not one per try.
#[test]
fn every_missing_required_key_is_reported_at_once() {
    let err = parse_scene("bare", "[initial]\npsi = 0.0\n[disk]\nm = 1.0\n", &[]).unwrap_err();
    let SceneError::Invalid { issues, .. } = &err else {
        panic!("{err}");
    };
    let keys: Vec<&str> = issues.iter().map(|i| i.key.as_str()).collect();
    let expected: Vec<&str> = REQUIRED_KEYS
        .iter()
        .copied()
        .filter(|k| *k != "disk.m")
        .collect();
    assert_eq!(keys, expected, "{err}");
    assert!(err.to_string().contains("is required"), "{err}");
}

/// `REQUIRED_KEYS` is what the scene's types require: a scene of the required keys alone
/// validates, dropping any one of them is an error naming exactly it, and every other key of
/// a full scene may be dropped.
#[test]
fn the_required_keys_are_exactly_those_without_defaults() {
    let full = parse_scene("tangent-toy", PAPER, &[]).unwrap();
    let tree: toml::Table = toml::from_str(&toml::to_string(&full.file).unwrap()).unwrap();
    let mut minimal = toml::Table::new();
    for path in REQUIRED_KEYS {
        let (table, key) = path.split_once('.').unwrap();
        let value = tree[table][key].clone();
        let entry = minimal
            .entry(table)
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        entry.as_table_mut().unwrap().insert(key.to_string(), value);
    }
    let text = toml::to_string(&minimal).unwrap();
    parse_scene("minimal", &text, &[]).unwrap_or_else(|e| panic!("{e}\n{text}"));
    for (table, keys) in &tree {
        let Some(keys) = keys.as_table() else {
            continue;
        };
        for key in keys.keys() {
            let path = format!("{table}.{key}");
            let mut without = tree.clone();
            let rest = without[table].as_table_mut().unwrap();
            rest.remove(key);
            // A table left empty stays, written as an empty table: its keys' defaults apply.
            let text = toml::to_string(&without).unwrap();
            let parsed = parse_scene("without", &text, &[]);
            if REQUIRED_KEYS.contains(&path.as_str()) {
                match parsed {
                    Err(SceneError::Invalid { issues, .. }) => {
                        let keys: Vec<&str> = issues.iter().map(|i| i.key.as_str()).collect();
                        assert_eq!(keys, [path.as_str()]);
                    }
                    other => panic!("{path}: {other:?}"),
                }
            } else {
                assert!(parsed.is_ok(), "{path} should have a default: {parsed:?}");
            }
        }
    }
}

/// The README's key table marks exactly the required keys, as `` `key` (**required** ``.
#[test]
fn the_readme_marks_the_required_keys() {
    let readme = include_str!("../../README.md");
    let marked = readme.matches("(**required**").count();
    assert_eq!(marked, REQUIRED_KEYS.len(), "one mark per required key");
    for path in REQUIRED_KEYS {
        let (table, key) = path.split_once('.').unwrap();
        let row = readme
            .lines()
            .find(|l| l.starts_with(&format!("| `[{table}]` |")))
            .unwrap_or_else(|| panic!("no row for [{table}]"));
        assert!(
            row.contains(&format!("`{key}` (**required**")),
            "{path} is not marked: {row}"
        );
    }
}

#[test]
fn a_modes_table_without_allowed_allows_both() {
    let without_modes = PAPER
        .lines()
        .filter(|l| !l.trim_start().starts_with("allowed"))
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        without_modes.contains("[modes]"),
        "the paper's scene names its modes"
    );
    let scene = parse_scene("t", &without_modes, &[]).unwrap_or_else(|e| panic!("{e}"));
    let full = parse_scene("t", PAPER, &[]).unwrap();
    assert_eq!(scene.file.settings.modes.allowed.len(), 2);
    assert_eq!(scene.file.settings.modes, full.file.settings.modes);
}
