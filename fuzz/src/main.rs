//! The fuzzer's command line (see the crate's documentation for what it does):
//!
//! ```text
//! fuzz [TARGET...|all] [--inputs N] [--seconds S] [--seed K]
//! fuzz TARGET --replay FILE...
//! ```
//!
//! Started as `fuzz --worker TARGET K START` it is a worker of the supervisor.

use std::process::ExitCode;
use std::time::Duration;

use eulerdisk_fuzz::supervisor::{supervise, work, Budget, Target};
use eulerdisk_fuzz::targets::{named, ALL};

const USAGE: &str = "usage: fuzz [TARGET...|all] [--inputs N] [--seconds S] [--seed K]\n       fuzz TARGET --replay FILE...";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [flag, target, seed, start] = args.as_slice() {
        if flag == "--worker" {
            let target = named(target).expect("a known target");
            let number = |s: &str| s.parse::<u64>().expect("a number");
            work(target, number(seed), number(start));
            return ExitCode::SUCCESS;
        }
    }
    if let [target, flag, files @ ..] = args.as_slice() {
        if flag == "--replay" {
            return replay(target, files);
        }
    }
    let (targets, budget) = match parse(&args) {
        Ok(parsed) => parsed,
        Err(message) => {
            eprintln!("{message}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    let mut findings = 0;
    for target in targets {
        let tally = supervise(target, budget);
        println!(
            "{}: {} inputs in {:.1} s ({:.0} inputs/s), {} finding(s)",
            target.name(),
            tally.inputs,
            tally.seconds,
            tally.inputs as f64 / tally.seconds.max(1e-9),
            tally.findings.len()
        );
        findings += tally.findings.len();
    }
    match findings {
        0 => ExitCode::SUCCESS,
        _ => ExitCode::FAILURE,
    }
}

/// Runs the saved inputs `files` through `target`'s check in this process, timed: a finding
/// reproduced (a panic shows its backtrace with `RUST_BACKTRACE=1`).
fn replay(target: &str, files: &[String]) -> ExitCode {
    let Some(target) = named(target) else {
        eprintln!("unknown target `{target}`\n{USAGE}");
        return ExitCode::from(2);
    };
    let mut wrong = 0;
    for file in files {
        let input = match std::fs::read_to_string(file) {
            Ok(input) => input,
            Err(e) => {
                eprintln!("{file}: {e}");
                return ExitCode::from(2);
            }
        };
        let started = std::time::Instant::now();
        let verdict = target.check(&input);
        let seconds = started.elapsed().as_secs_f64();
        match verdict {
            Ok(()) => println!("{file}: ok in {seconds:.3} s"),
            Err(e) => {
                println!("{file}: wrong in {seconds:.3} s: {e}");
                wrong += 1;
            }
        }
    }
    match wrong {
        0 => ExitCode::SUCCESS,
        _ => ExitCode::FAILURE,
    }
}

/// The targets and the budget the arguments ask for.
fn parse(args: &[String]) -> Result<(Vec<&'static dyn Target>, Budget), String> {
    let mut targets: Vec<&'static dyn Target> = Vec::new();
    let (mut seconds, mut inputs, mut seed) = (None, None, 1u64);
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        let mut value = |flag: &str| {
            rest.next()
                .ok_or(format!("{flag} needs a value"))
                .and_then(|v| {
                    v.parse::<f64>()
                        .map_err(|_| format!("{flag}: `{v}` is not a number"))
                })
                .and_then(|v| match v.is_finite() && v >= 0.0 {
                    true => Ok(v),
                    false => Err(format!("{flag} must be a finite number >= 0")),
                })
        };
        match arg.as_str() {
            "--seconds" => seconds = Some(value("--seconds")?),
            "--inputs" => inputs = Some(value("--inputs")? as u64),
            "--seed" => seed = value("--seed")? as u64,
            "all" => targets.extend(ALL),
            name => targets.push(named(name).ok_or_else(|| {
                let names: Vec<&str> = ALL.iter().map(|t| t.name()).collect();
                format!("unknown target `{name}` (targets: {})", names.join(", "))
            })?),
        }
    }
    if targets.is_empty() {
        targets.extend(ALL);
    }
    let default = if inputs.is_some() { 1e9 } else { 10.0 };
    let budget = Budget {
        time: Duration::from_secs_f64(seconds.unwrap_or(default)),
        inputs: inputs.unwrap_or(u64::MAX),
        seed,
    };
    Ok((targets, budget))
}
