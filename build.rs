//! Puts the git commit into `--version` when built from a checkout.
//!
//! `VPX_EFIS_VERSION` is `0.1.0 (abc1234)` when `git rev-parse --short HEAD` works, and
//! plain `0.1.0` otherwise: a build from a source tarball, from crates.io, or on a machine
//! without git simply has no commit.
//!
//! Built for Windows with the GNU toolchain, the exe also carries its version in its
//! Windows properties (Explorer's Details tab), from a resource compiled by mingw's
//! `windres`. Nothing of it runs for any other target: `cargo run` on Linux or macOS
//! needs no new tool.

use std::path::PathBuf;
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let version = std::env::var("CARGO_PKG_VERSION").unwrap_or_default();
    windows_version_resource(&version);
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

/// The VERSIONINFO resource of the Windows exe (GNU toolchain: mingw's windres). A
/// missing windres is a warning, not a failed build: the exe then only lacks its
/// properties.
fn windows_version_resource(version: &str) {
    let var = |k: &str| std::env::var(k).unwrap_or_default();
    if var("CARGO_CFG_TARGET_OS") != "windows" || var("CARGO_CFG_TARGET_ENV") != "gnu" {
        return;
    }
    println!("cargo:rerun-if-env-changed=WINDRES");
    let mut nums = version
        .split(['.', '-', '+'])
        .map(|n| n.parse::<u16>().unwrap_or(0));
    let (a, b, c) = (
        nums.next().unwrap_or(0),
        nums.next().unwrap_or(0),
        nums.next().unwrap_or(0),
    );
    let description = var("CARGO_PKG_DESCRIPTION").replace('"', "'");
    let rc = format!(
        r#"#include <winver.h>
1 VERSIONINFO
FILEVERSION {a},{b},{c},0
PRODUCTVERSION {a},{b},{c},0
FILEOS VOS_NT_WINDOWS32
FILETYPE VFT_APP
BEGIN
  BLOCK "StringFileInfo"
  BEGIN
    BLOCK "040904b0"
    BEGIN
      VALUE "CompanyName", "vpx-efis"
      VALUE "FileDescription", "{description}"
      VALUE "FileVersion", "{version}"
      VALUE "InternalName", "vpx-efis"
      VALUE "LegalCopyright", "MIT OR Apache-2.0"
      VALUE "OriginalFilename", "vpx-efis.exe"
      VALUE "ProductName", "vpx-efis"
      VALUE "ProductVersion", "{version}"
    END
  END
  BLOCK "VarFileInfo"
  BEGIN
    VALUE "Translation", 0x409, 1200
  END
END
"#
    );
    let out = PathBuf::from(var("OUT_DIR"));
    let rc_path = out.join("version.rc");
    let obj = out.join("version-res.o");
    if let Err(e) = std::fs::write(&rc_path, rc) {
        println!("cargo:warning=version resource not made: {e}");
        return;
    }
    // A cross build (from Linux) has the prefixed name; mingw on Windows the plain one.
    let windres = std::env::var("WINDRES").ok().unwrap_or_else(|| {
        if var("HOST").contains("windows") {
            "windres".into()
        } else {
            format!("{}-w64-mingw32-windres", var("CARGO_CFG_TARGET_ARCH"))
        }
    });
    let made = Command::new(&windres)
        .args(["-O", "coff", "-i"])
        .arg(&rc_path)
        .arg("-o")
        .arg(&obj)
        .status();
    match made {
        Ok(s) if s.success() => {
            println!("cargo:rustc-link-arg-bins={}", obj.display());
        }
        Ok(s) => println!("cargo:warning=version resource not made: {windres} exited {s}"),
        Err(e) => println!("cargo:warning=version resource not made: {windres}: {e}"),
    }
}
