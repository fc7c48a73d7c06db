//! A fuzzer for the DSL's front end and compiler that runs on stable Rust.
//!
//! ```text
//! cargo run --release -p model-dsl --example fuzz -- [front|compile|eval|all] [--seconds S] [--inputs N] [--seed K]
//! ```
//!
//! Each input is a seed model of `model-macros/dsl/fuzz/corpus/` mutated a few times (tokens
//! deleted, repeated, swapped, spliced from another seed, replaced by a keyword, an operator,
//! an extreme number or a stray character, or wrapped in deep nesting), deterministically from
//! the seed `K` and the input's index. The targets:
//!
//! - `front`: parse and validate (the model and its switched form);
//! - `compile`: the whole pipeline, as `model!` and `eulerdisk model` run it;
//! - `eval`: the compiled programs (right-hand side, Jacobian, outputs) at extreme states and
//!   parameters (zeros, signed zeros, subnormals, ±1e308, infinities, NaN, multiples of π).
//!
//! Every input must give a model or errors: a panic, a stack overflow (the inputs run on a
//! thread with an 8 MiB stack, rustc's) or an input that takes longer than 10 s is a finding.
//! The inputs run in a child process that reports each index before running it, so the
//! supervisor knows the input that crashed or hung, saves it under `fuzz/findings/`, and goes
//! on from the next one. A finding, once fixed, is copied into `fuzz/corpus/` (a seed of its
//! own from then on) with a regression test. The exit status is nonzero if anything was found.

use model_algebra::{CompiledModel, Inputs};
use model_dsl::Source;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// The longest one input may take before it counts as a hang.
const HANG: Duration = Duration::from_secs(10);
/// The stack of the thread the inputs run on.
const STACK: usize = 8 << 20;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let corpus = load_corpus();
    if args.first().map(String::as_str) == Some("--worker") {
        let number = |k: usize| args[k].parse::<u64>().expect("a number");
        let (target, seed, start) = (args[1].clone(), number(2), number(3));
        let child = std::thread::Builder::new().stack_size(STACK);
        let run = move || worker(&target, seed, start, &corpus);
        child.spawn(run).expect("thread").join().expect("no panic");
        return;
    }
    let mut targets = Vec::new();
    let (mut seconds, mut inputs, mut seed) = (None, None, 1u64);
    let mut k = 0;
    while k < args.len() {
        let value = |k: usize| args.get(k + 1).and_then(|v| v.parse::<f64>().ok());
        match args[k].as_str() {
            "--seconds" => seconds = value(k),
            "--inputs" => inputs = value(k).map(|n| n as u64),
            "--seed" => seed = value(k).map_or(1, |s| s as u64),
            "all" => targets.extend(["front", "compile", "eval"]),
            name @ ("front" | "compile" | "eval") => targets.push(match name {
                "front" => "front",
                "compile" => "compile",
                _ => "eval",
            }),
            other => {
                eprintln!("unknown argument `{other}`: [front|compile|eval|all] [--seconds S] [--inputs N] [--seed K]");
                std::process::exit(2);
            }
        }
        k += if args[k].starts_with("--") { 2 } else { 1 };
    }
    if targets.is_empty() {
        targets.extend(["front", "compile", "eval"]);
    }
    let budget =
        Duration::from_secs_f64(seconds.unwrap_or(if inputs.is_some() { 1e9 } else { 10.0 }));
    let mut found = 0;
    for target in targets {
        found += supervise(target, seed, budget, inputs.unwrap_or(u64::MAX), &corpus);
    }
    if found > 0 {
        std::process::exit(1);
    }
}

/// The seed models.
fn load_corpus() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("the corpus directory")
        .filter_map(|e| Some(e.ok()?.path()))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| std::fs::read_to_string(p).expect("a seed"))
        .collect()
}

/// Runs `target` in child processes until the budget is spent; returns the number of findings.
fn supervise(target: &str, seed: u64, budget: Duration, inputs: u64, corpus: &[String]) -> usize {
    let started = Instant::now();
    let (mut next, mut done, mut findings) = (0u64, 0u64, 0usize);
    while started.elapsed() < budget && done < inputs {
        let mut child = Command::new(std::env::current_exe().expect("this program"))
            .args(["--worker", target, &seed.to_string(), &next.to_string()])
            .stdout(Stdio::piped())
            .spawn()
            .expect("a worker");
        let mut out = child.stdout.take().expect("its output");
        let (send, receive) = mpsc::channel();
        std::thread::spawn(move || {
            let mut index = [0u8; 8];
            while out.read_exact(&mut index).is_ok() {
                if send.send(u64::from_le_bytes(index)).is_err() {
                    break;
                }
            }
        });
        let mut last = None;
        let verdict = loop {
            if started.elapsed() >= budget || done >= inputs {
                break None;
            }
            match receive.recv_timeout(HANG) {
                Ok(index) => {
                    last = Some(index);
                    done += 1;
                }
                Err(mpsc::RecvTimeoutError::Timeout) => break Some("hang"),
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    let status = child.wait().expect("the worker's status");
                    break (!status.success()).then_some("crash");
                }
            }
        };
        let _ = child.kill();
        let _ = child.wait();
        let (Some(kind), Some(index)) = (verdict, last) else {
            break;
        };
        findings += 1;
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fuzz/findings")
            .join(format!("{target}-{kind}-seed{seed}-{index}.dsl"));
        let _ = std::fs::create_dir_all(path.parent().expect("a directory"));
        let _ = std::fs::write(&path, input(seed, index, corpus));
        eprintln!(
            "{target}: {kind} on input {index}, saved as {}",
            path.display()
        );
        next = index + 1;
    }
    let seconds = started.elapsed().as_secs_f64();
    println!(
        "{target}: {done} inputs in {seconds:.1} s ({:.0} inputs/s), {findings} finding(s)",
        done as f64 / seconds
    );
    findings
}

/// Runs inputs `start..` of `target`, announcing each index on standard output first.
fn worker(target: &str, seed: u64, start: u64, corpus: &[String]) {
    let mut out = std::io::stdout().lock();
    for index in start.. {
        if out
            .write_all(&index.to_le_bytes())
            .and_then(|()| out.flush())
            .is_err()
        {
            return;
        }
        let text = input(seed, index, corpus);
        match target {
            "front" => front(&text),
            "compile" => {
                compile(&text);
            }
            _ => {
                for model in compile(&text) {
                    evaluate(&model);
                }
            }
        }
    }
}

fn switched(text: &str) -> bool {
    text.contains("mode") || text.contains("when")
}

fn front(text: &str) {
    let source = Source::new("fuzz.dsl", text);
    if let Ok(ast) = source.parse() {
        let _ = model_dsl::validate(&ast);
        if switched(text) {
            let _ = model_dsl::validate_switched(&ast);
        }
    }
}

fn compile(text: &str) -> Vec<CompiledModel> {
    let source = Source::new("fuzz.dsl", text);
    if switched(text) {
        let _ = source.compile_switched();
    }
    match source.compile() {
        Ok(models) => models.into_iter().map(|m| m.compiled).collect(),
        Err(_) => Vec::new(),
    }
}

/// Values that break careless arithmetic.
const EXTREMES: [f64; 14] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    5e-324,
    1e-308,
    1e308,
    -1e308,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    std::f64::consts::PI,
    std::f64::consts::FRAC_PI_2,
    1e16,
];

fn evaluate(model: &CompiledModel) {
    let n = model.states.len();
    let defaults: Vec<f64> = model.params.iter().map(|(_, v)| v.unwrap_or(1.0)).collect();
    for (k, &x) in EXTREMES.iter().enumerate() {
        let states: Vec<f64> = (0..n)
            .map(|i| {
                if i % 2 == 0 {
                    x
                } else {
                    EXTREMES[(k + i) % 14]
                }
            })
            .collect();
        for params in [defaults.clone(), vec![x; defaults.len()]] {
            let inputs = Inputs {
                t: x,
                states: &states,
                params: &params,
                ders: &[],
            };
            let ders = match model.rhs.eval(&inputs) {
                Ok(stores) => stores.ders(n),
                Err(_) => vec![x; n],
            };
            let _ = model.jacobian.eval(&inputs);
            let with_ders = Inputs {
                ders: &ders,
                ..inputs
            };
            let _ = model.outputs_program.eval(&with_ders);
        }
    }
}

/// Input `index` of the run seeded with `seed`: a seed model, mutated.
fn input(seed: u64, index: u64, corpus: &[String]) -> String {
    let mut rng = Rng(seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let base = &corpus[rng.below(corpus.len())];
    let mut tokens = split(base);
    for _ in 0..1 + rng.below(6) {
        mutate(&mut tokens, &mut rng, corpus);
    }
    tokens.concat()
}

/// Tokens to insert: the DSL's words and operators, Rust keywords, extreme numbers, strays.
const DICTIONARY: &[&str] = &[
    "mod",
    "pub",
    "params",
    "states",
    "let",
    "equations",
    "outputs",
    "variant",
    "keep",
    "fix",
    "chart",
    "replace",
    "after",
    "options",
    "mode",
    "when",
    "accumulates",
    "stop",
    "der",
    "sin",
    "cos",
    "tan",
    "sqrt",
    "exp",
    "ln",
    "abs",
    "atan2",
    "sign",
    "min",
    "max",
    "if",
    "t",
    "pi",
    "type",
    "in",
    "loop",
    "self",
    "_",
    "x",
    "y",
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    ",",
    ";",
    ":",
    "=",
    "==",
    "<",
    "<=",
    ">",
    ">=",
    "+",
    "-",
    "*",
    "/",
    "^",
    "**",
    ".",
    "->",
    "#",
    "'",
    "\"",
    "/*",
    "//",
    "\n",
    "²",
    "1e308",
    "1e-308",
    "5e-324",
    "0",
    "-0.0",
    "1e16",
    "1e400",
    "0.5",
    "2",
    "swell_bound",
    "pivot_tolerance",
    "1u8",
    "0x10",
    "///",
    "!",
];

fn mutate(tokens: &mut Vec<String>, rng: &mut Rng, corpus: &[String]) {
    if tokens.is_empty() {
        tokens.push(DICTIONARY[rng.below(DICTIONARY.len())].to_string());
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
            let times = 1 + rng.below(4);
            for _ in 0..times {
                tokens.splice(at..at, copy.clone());
            }
        }
        2 => {
            let word = DICTIONARY[rng.below(DICTIONARY.len())];
            tokens.insert(at, word.to_string());
        }
        3 => {
            let word = DICTIONARY[rng.below(DICTIONARY.len())];
            tokens[at] = word.to_string();
        }
        4 => {
            let other = rng.below(tokens.len());
            tokens.swap(at, other);
        }
        5 => {
            let donor = split(&corpus[rng.below(corpus.len())]);
            let from = rng.below(donor.len().max(1));
            let to = (from + 1 + rng.below(20)).min(donor.len());
            tokens.splice(at..at, donor[from.min(to)..to].to_vec());
        }
        6 => {
            let depth = 1 + rng.below(400);
            let (open, close) = [
                ("(", ")"),
                ("sin(", ")"),
                ("der(", ")"),
                ("-", ""),
                ("x^", ""),
                ("x + ", ""),
                ("if(x > 0, ", ", 1)"),
            ][rng.below(7)];
            tokens.insert(at, open.repeat(depth));
            tokens.insert((at + 1 + len).min(tokens.len()), close.repeat(depth));
        }
        7 => {
            let numbers: Vec<usize> = (0..tokens.len())
                .filter(|&k| tokens[k].starts_with(|c: char| c.is_ascii_digit()))
                .collect();
            if !numbers.is_empty() {
                let k = numbers[rng.below(numbers.len())];
                tokens[k] = ["1e308", "1e-308", "0", "1e16", "4.9e-324", "1e300", "0.0"]
                    [rng.below(7)]
                .into();
            }
        }
        _ => {
            let c = ['²', '\'', '#', '"', '\u{0}', 'θ', '·', '\\', '@', '$', '`'][rng.below(11)];
            tokens.insert(at, c.to_string());
        }
    }
}

/// Words (names and numbers), runs of white space and single other characters.
fn split(text: &str) -> Vec<String> {
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

/// SplitMix64: small, fast and deterministic.
#[derive(Clone)]
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}
