//! The commands of README.md and model-macros/DSL.md run as written. Every fenced block marked
//! ```` ```sh runnable ```` (or ```` ```sh runnable exit=N ```` for a command documented to end
//! with another exit code) is run, command by command, by `sh` in a fresh folder that holds the
//! repository's files, with the built `eulerdisk` first on the `PATH`, as after the README's
//! `cargo install --path .`. `cargo run --release --` at the start of a command stands for that
//! same binary (`cargo` itself is not run again from inside its own tests).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The documents whose runnable blocks are run, relative to the repository.
const DOCUMENTS: [&str; 2] = ["README.md", "model-macros/DSL.md"];

/// The info string that marks a block as runnable.
const MARK: &str = "```sh runnable";

/// One command of a runnable block: where it is, what it runs, the exit code it must give.
#[derive(Debug)]
struct Documented {
    place: String,
    command: String,
    exit: i32,
}

/// The commands of every runnable block of `text`: continuation lines (`\` at the end) joined,
/// comments and blank lines dropped.
fn runnable_commands(document: &str, text: &str) -> Vec<Documented> {
    let mut found = Vec::new();
    let mut lines = text.lines().enumerate();
    while let Some((number, line)) = lines.next() {
        let Some(options) = line.trim_start().strip_prefix(MARK) else {
            continue;
        };
        let exit = options
            .split_whitespace()
            .find_map(|o| o.strip_prefix("exit="))
            .map_or(0, |code| code.parse().expect("exit=N takes an integer"));
        let mut command = String::new();
        for (_, line) in lines.by_ref() {
            if line.trim_start().starts_with("```") {
                break;
            }
            if let Some(head) = line.trim_end().strip_suffix('\\') {
                command.push_str(head);
                command.push(' ');
                continue;
            }
            command.push_str(line);
            let whole = std::mem::take(&mut command);
            let whole = whole.trim();
            if !whole.is_empty() && !whole.starts_with('#') {
                found.push(Documented {
                    place: format!("{document}:{}", number + 1),
                    command: whole.to_string(),
                    exit,
                });
            }
        }
    }
    found
}

/// A fresh folder in which every top-level entry of the repository (but its build output) is
/// a link to the original, so commands read the repository's files and write only here.
fn fresh_clone(repository: &Path) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for entry in std::fs::read_dir(repository).unwrap() {
        let entry = entry.unwrap();
        let name = entry.file_name();
        if ["target", "out", ".git"].iter().any(|n| name == *n) {
            continue;
        }
        std::os::unix::fs::symlink(entry.path(), dir.path().join(&name)).unwrap();
    }
    dir
}

fn binary_dir() -> PathBuf {
    Path::new(env!("CARGO_BIN_EXE_eulerdisk"))
        .parent()
        .unwrap()
        .to_path_buf()
}

#[test]
fn the_documented_commands_run_as_written() {
    let repository = Path::new(env!("CARGO_MANIFEST_DIR"));
    let commands: Vec<Documented> = DOCUMENTS
        .iter()
        .flat_map(|doc| {
            let text = std::fs::read_to_string(repository.join(doc)).unwrap();
            runnable_commands(doc, &text)
        })
        .collect();
    assert!(commands.len() >= 8, "{commands:?}");
    let clone = fresh_clone(repository);
    let path = std::env::join_paths(std::iter::once(binary_dir()).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .unwrap();
    for documented in &commands {
        let command = documented
            .command
            .strip_prefix("cargo run --release -- ")
            .map_or(documented.command.clone(), |rest| {
                format!("eulerdisk {rest}")
            });
        assert!(
            command.starts_with("eulerdisk "),
            "{}: a runnable command is an `eulerdisk` command: {command}",
            documented.place
        );
        let out = Command::new("sh")
            .args(["-c", &command])
            .current_dir(clone.path())
            .env("PATH", &path)
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(documented.exit),
            "{}: `{command}`\n{}",
            documented.place,
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn blocks_are_read_with_their_continuations_and_exit_codes() {
    let text = "x\n```sh runnable exit=3\n# a comment\neulerdisk a \\\n    --b c   # says\n\neulerdisk d\n```\n```sh\neulerdisk e\n```\n";
    let found = runnable_commands("T.md", text);
    let commands: Vec<(&str, i32)> = found.iter().map(|d| (d.command.as_str(), d.exit)).collect();
    assert_eq!(
        commands,
        [("eulerdisk a      --b c   # says", 3), ("eulerdisk d", 3)]
    );
    assert_eq!(found[0].place, "T.md:2");
}

/// Whether `path` (relative to `repository`; one `*` in its file name matches any text) names
/// a file.
fn exists(repository: &Path, path: &str) -> bool {
    let Some((head, tail)) = path.split_once('*') else {
        return repository.join(path).is_file();
    };
    let (dir, start) = head.rsplit_once('/').unwrap_or(("", head));
    std::fs::read_dir(repository.join(dir)).is_ok_and(|entries| {
        entries.filter_map(Result::ok).any(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.starts_with(start)
                && name.ends_with(tail)
                && name.len() >= start.len() + tail.len()
        })
    })
}

/// Every repository path README.md names (`` `dir/file.ext` `` or a link `(dir/file.md)`) is
/// a file of the repository (a `*` matching at least one); output files (`out/...`) are made by the commands, not named here.
#[test]
fn every_file_the_readme_names_exists() {
    let repository = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(repository.join("README.md")).unwrap();
    const EXTENSIONS: [&str; 7] = [".rs", ".md", ".toml", ".dsl", ".sh", ".yaml", ".png"];
    let path_like = |token: &str| {
        token.contains('/')
            && !token.starts_with("out/")
            && !token.contains(' ')
            && EXTENSIONS.iter().any(|e| token.ends_with(e))
    };
    let quoted = readme.split('`').skip(1).step_by(2);
    let linked = readme
        .split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next());
    let named: Vec<&str> = quoted.chain(linked).filter(|t| path_like(t)).collect();
    assert!(named.len() >= 15, "{named:?}");
    let missing: Vec<&&str> = named
        .iter()
        .filter(|path| !exists(repository, path))
        .collect();
    assert!(
        missing.is_empty(),
        "README.md names files that do not exist: {missing:?}"
    );
}
