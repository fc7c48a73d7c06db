//! The harness: runs a target's inputs in child processes and attributes every crash, hang
//! and wrong answer to the input that caused it.
//!
//! A stack overflow or an abort kills the process it happens in, and a hang never returns, so
//! the inputs cannot run in the supervising process. A worker (this program, started again
//! with `--worker`) runs inputs `start..` of one target on a thread with rustc's 8 MiB stack,
//! in an empty folder of its own, and writes each input's index to its standard output
//! before running it. The supervisor reads the indices: when the worker dies, or is silent
//! for longer than [`HANG`], the last index it announced is the finding. The input is saved
//! under `fuzz/findings/`, and a new worker goes on from the next index, so one bad input
//! does not end the campaign. A target's check that fails without crashing (an `Ok` carrying
//! a NaN, a listed point the loader refuses) ends the worker with [`WRONG`]; a file left in
//! the worker's folder is a finding too (bad input must leave nothing written).

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{mpsc, OnceLock};
use std::time::{Duration, Instant};

use crate::rng::Rng;

/// The longest one input may take before it counts as a hang.
pub const HANG: Duration = Duration::from_secs(10);
/// The stack of the thread the inputs run on (rustc's, which runs `model!`).
pub const STACK: usize = 8 << 20;
/// The exit status of a worker whose target gave a wrong answer (not a crash).
pub const WRONG: i32 = 3;

/// One fuzz target: how its inputs are made and what each must satisfy.
pub trait Target: Sync {
    /// Its name on the command line.
    fn name(&self) -> &'static str;
    /// The extension of its saved inputs (`dsl`, `toml`, `txt`).
    fn extension(&self) -> &'static str;
    /// Its seeds.
    fn seeds(&self) -> &[String];
    /// Input number `index` of a run: a function of `rng` alone, so it can be made again.
    fn input(&self, rng: &mut Rng) -> String;
    /// Runs one input. A value or a clear error is `Ok`; a result that is wrong without
    /// crashing (a non-finite number in an `Ok`, say) is `Err` with the sentence that says so.
    /// A panic, an abort or a hang is caught by the supervisor.
    fn check(&self, input: &str) -> Result<(), String>;
}

/// The folder of the fuzz crate (corpora, findings).
pub fn home() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A target's seeds: every file of its folders (relative to the workspace's root), read on
/// first use and sorted by path, so the seeds' order, and with it every input, is fixed.
#[derive(Debug)]
pub struct Corpus {
    dirs: &'static [&'static str],
    texts: OnceLock<Vec<String>>,
}

impl Corpus {
    /// The seeds in `dirs`.
    pub const fn new(dirs: &'static [&'static str]) -> Corpus {
        Corpus {
            dirs,
            texts: OnceLock::new(),
        }
    }

    /// The seeds' texts.
    pub fn texts(&self) -> &[String] {
        self.texts.get_or_init(|| {
            let root = home().parent().expect("the workspace's root");
            let mut paths: Vec<PathBuf> = (self.dirs.iter())
                .flat_map(|d| std::fs::read_dir(root.join(d)).expect("a corpus folder"))
                .filter_map(|e| Some(e.ok()?.path()))
                .filter(|p| p.is_file())
                .collect();
            paths.sort();
            paths
                .iter()
                .map(|p| std::fs::read_to_string(p).expect("a seed"))
                .collect()
        })
    }
}

/// How much one target runs.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// Stop after this long.
    pub time: Duration,
    /// Stop after this many inputs (the deterministic budget).
    pub inputs: u64,
    /// The run's seed.
    pub seed: u64,
}

/// What one target's run did.
#[derive(Clone, Debug, PartialEq)]
pub struct Tally {
    /// Inputs run.
    pub inputs: u64,
    /// Wall time, s.
    pub seconds: f64,
    /// The saved findings.
    pub findings: Vec<PathBuf>,
}

/// Runs `target` in workers until `budget` is spent; saves and counts the findings.
pub fn supervise(target: &dyn Target, budget: Budget) -> Tally {
    let started = Instant::now();
    let (mut next, mut done, mut findings) = (0u64, 0u64, Vec::new());
    let spent = |done: u64| started.elapsed() >= budget.time || done >= budget.inputs;
    let folder = std::env::temp_dir().join(format!(
        "eulerdisk-fuzz-{}-{}",
        std::process::id(),
        target.name()
    ));
    while !spent(done) {
        let _ = std::fs::remove_dir_all(&folder);
        std::fs::create_dir_all(&folder).expect("the worker's folder");
        let mut child = Command::new(std::env::current_exe().expect("this program"))
            .args(["--worker", target.name()])
            .args([budget.seed.to_string(), next.to_string()])
            .current_dir(&folder)
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
            if spent(done) {
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
                    break match status.code() {
                        Some(0) => None,
                        Some(WRONG) => Some("wrong"),
                        _ => Some("crash"),
                    };
                }
            }
        };
        let _ = child.kill();
        let _ = child.wait();
        let (Some(kind), Some(index)) = (verdict, last) else {
            break;
        };
        let name = target.name();
        let path = home().join("findings").join(format!(
            "{name}-{kind}-seed{}-{index}.{}",
            budget.seed,
            target.extension()
        ));
        let _ = std::fs::create_dir_all(path.parent().expect("a folder"));
        let input = target.input(&mut Rng::for_input(budget.seed, index));
        let _ = std::fs::write(&path, input);
        eprintln!(
            "{name}: {kind} on input {index}, saved as {}",
            path.display()
        );
        findings.push(path);
        next = index + 1;
    }
    let _ = std::fs::remove_dir_all(&folder);
    Tally {
        inputs: done,
        seconds: started.elapsed().as_secs_f64(),
        findings,
    }
}

/// The worker: runs inputs `start..` of `target` in the current folder, announcing each index
/// on standard output first; returns only when the supervisor stops listening.
pub fn work(target: &'static dyn Target, seed: u64, start: u64) {
    let thread = std::thread::Builder::new().stack_size(STACK);
    let run = move || {
        let mut out = std::io::stdout().lock();
        for index in start.. {
            let announced = out
                .write_all(&index.to_le_bytes())
                .and_then(|()| out.flush());
            if announced.is_err() {
                return;
            }
            let input = target.input(&mut Rng::for_input(seed, index));
            let verdict = target.check(&input).and_then(|()| nothing_written());
            if let Err(wrong) = verdict {
                eprintln!("{}: input {index}: {wrong}", target.name());
                std::process::exit(WRONG);
            }
        }
    };
    let finished = thread.spawn(run).expect("a thread").join();
    if finished.is_err() {
        std::process::exit(101);
    }
}

/// `Err` naming the files an input left in the worker's (empty) folder.
fn nothing_written() -> Result<(), String> {
    let left: Vec<String> = std::fs::read_dir(".")
        .map_err(|e| format!("the worker's folder cannot be read: {e}"))?
        .filter_map(|e| Some(e.ok()?.file_name().to_string_lossy().into_owned()))
        .collect();
    match left.is_empty() {
        true => Ok(()),
        false => Err(format!("the input left files behind: {}", left.join(", "))),
    }
}
