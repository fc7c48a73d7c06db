//! Records the git revision the program is built from, so that a run's `summary.json` can say
//! which code produced it. Built outside a git checkout (a source archive, no `git` installed)
//! the revision reads `unknown (built without git)`.

use std::path::PathBuf;
use std::process::Command;

/// Runs `git` with `args` in the package directory; its trimmed output, if it succeeded.
fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    let text = text.trim();
    (out.status.success() && !text.is_empty()).then(|| text.to_string())
}

fn main() {
    let revision = git(&["rev-parse", "--short=12", "HEAD"])
        .unwrap_or_else(|| "unknown (built without git)".into());
    println!("cargo:rustc-env=EULERDISK_GIT_REVISION={revision}");
    println!("cargo:rerun-if-changed=build.rs");
    // Build again when HEAD moves: a new commit on the branch, or another branch checked out.
    // (Only files that exist: a missing one would make every build rerun this script.)
    let mut watched = Vec::new();
    if let Some(dir) = git(&["rev-parse", "--git-dir"]) {
        watched.push(PathBuf::from(dir).join("HEAD"));
    }
    if let (Some(common), Some(head)) = (
        git(&["rev-parse", "--git-common-dir"]),
        git(&["symbolic-ref", "-q", "HEAD"]),
    ) {
        let common = PathBuf::from(common);
        watched.push(common.join(head));
        watched.push(common.join("packed-refs"));
    }
    for path in watched.iter().filter(|p| p.is_file()) {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}
