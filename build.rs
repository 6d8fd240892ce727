//! Puts the git commit into `--version` when built from a checkout.
//!
//! `VPX_EFIS_VERSION` is `0.1.0 (abc1234)` when `git rev-parse --short HEAD` works, and
//! plain `0.1.0` otherwise: a build from a source tarball, from crates.io, or on a machine
//! without git simply has no commit.

use std::path::PathBuf;
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let version = std::env::var("CARGO_PKG_VERSION").unwrap_or_default();
    // Only our own checkout counts: a copy of the crate inside some other repository
    // (vendored, or unpacked under a home directory kept in git) has no commit of ours.
    let ours = git(&["rev-parse", "--show-toplevel"]).is_some_and(|top| {
        let manifest = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
        same_dir(&top, &manifest)
    });
    let commit = if ours {
        git(&["rev-parse", "--short", "HEAD"])
    } else {
        None
    };
    let Some(commit) = commit else {
        println!("cargo:rustc-env=VPX_EFIS_VERSION={version}");
        return;
    };
    println!("cargo:rustc-env=VPX_EFIS_VERSION={version} ({commit})");
    // Rebuild when HEAD moves: HEAD itself (a checkout), the branch it points at (a
    // commit), and packed-refs (a gc). Paths come from git, so worktrees work too.
    let mut watch = vec!["HEAD".to_string(), "packed-refs".to_string()];
    if let Some(branch) = git(&["symbolic-ref", "-q", "HEAD"]) {
        watch.push(branch);
    }
    for name in watch {
        if let Some(path) = git(&["rev-parse", "--git-path", &name]) {
            let path = PathBuf::from(path);
            if path.exists() {
                println!("cargo:rerun-if-changed={}", path.display());
            }
        }
    }
}

/// One line of git's output, or `None` when git is missing or fails (no checkout).
fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    if !out.status.success() {
        return None;
    }
    let line = String::from_utf8(out.stdout).ok()?.trim().to_string();
    (!line.is_empty()).then_some(line)
}

fn same_dir(a: &str, b: &str) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}
