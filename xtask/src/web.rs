//! `cargo xtask web`: the browser page (crates/web compiled to WebAssembly, and `web/`) built
//! into one folder, `target/web/site`, that any static server serves or a browser opens from
//! disk (`index.html`); `cargo xtask web-test` (a step of `ci`) builds it and runs the
//! browser test of `web/test` on it.
//!
//! The build: `cargo build -p karman-web --target wasm32-unknown-unknown --release`, then the
//! `wasm-bindgen` of the very version Cargo.lock holds (`--target no-modules`: plain scripts,
//! which a page opened from disk may load where modules may not), installed into
//! `target/web/tools` with `cargo install` when no such program is there (nor on the PATH, nor
//! named by `KARMAN_WASM_BINDGEN`). The module itself is
//! written as a script too (`karman_wasm.js`, its bytes in base64), so the page needs no
//! `fetch`, which a page opened from disk is refused.
//!
//! The test (`web/test/browser.mjs`, Node with `playwright-core`) drives the system's
//! Chromium (`/usr/bin/chromium`, installed with apt when missing and `CI` is set); without
//! Chromium or Node locally it is skipped with a message, and with `CI` set that fails.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// The version of the `wasm-bindgen` crate in Cargo.lock.
fn bindgen_version(root: &Path) -> Result<String> {
    let lock =
        std::fs::read_to_string(root.join("Cargo.lock")).context("cannot read Cargo.lock")?;
    let mut lines = lock.lines();
    while let Some(line) = lines.next() {
        if line == "name = \"wasm-bindgen\""
            && let Some(version) = lines
                .next()
                .and_then(|l| l.strip_prefix("version = \""))
                .and_then(|l| l.strip_suffix('"'))
        {
            return Ok(version.to_owned());
        }
    }
    bail!("Cargo.lock has no wasm-bindgen package")
}

/// The output of `program --version`, when it runs.
fn version_of(program: &Path) -> Option<String> {
    let out = crate::child_command(program)
        .arg("--version")
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

/// A `wasm-bindgen` of `version`: `target/web/tools/bin/wasm-bindgen`, installed there from
/// the crate registry when it is missing or of another version.
fn wasm_bindgen(root: &Path, version: &str) -> Result<PathBuf> {
    let tools = crate::target_dir(root).join("web/tools");
    let program = tools.join("bin/wasm-bindgen");
    let wanted = format!("wasm-bindgen {version}");
    // `KARMAN_WASM_BINDGEN`, or one on the PATH, of that version saves the install.
    let given = std::env::var_os("KARMAN_WASM_BINDGEN").map(PathBuf::from);
    for candidate in given
        .into_iter()
        .chain([PathBuf::from("wasm-bindgen"), program.clone()])
    {
        if version_of(&candidate).as_deref() == Some(wanted.as_str()) {
            return Ok(candidate);
        }
    }
    let tools_text = tools.display().to_string();
    let install = |locked: bool| {
        let mut args = vec!["install", "wasm-bindgen-cli", "--version", version];
        if locked {
            args.push("--locked");
        }
        args.extend(["--root", &tools_text, "--force"]);
        // Its own target folder: the workspace's build is not disturbed.
        let target = tools.join("build").display().to_string();
        crate::cargo_with(root, &args, &[("CARGO_TARGET_DIR", &target)])
    };
    // The locked versions first; a registry without one of them (a mirror that lags) gets
    // the newest compatible ones.
    if let Err(e) = install(true) {
        eprintln!("xtask: {e:#}; installing without --locked");
        install(false)?;
    }
    match version_of(&program) {
        Some(found) if found == wanted => Ok(program),
        found => bail!("{} is {found:?}, not {wanted}", program.display()),
    }
}

/// Standard base64 (RFC 4648, with padding).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (i, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if i <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> shift) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Builds the page into `target/web/site` and returns that folder.
pub fn build(root: &Path) -> Result<PathBuf> {
    let version = bindgen_version(root)?;
    let bindgen = wasm_bindgen(root, &version)?;
    crate::cargo(
        root,
        &[
            "build",
            "--package",
            "karman-web",
            "--target",
            "wasm32-unknown-unknown",
            "--release",
        ],
    )?;
    let target = crate::target_dir(root);
    let wasm = target.join("wasm32-unknown-unknown/release/karman_web.wasm");
    let out = target.join("web");
    let pkg = out.join("pkg");
    let status = crate::child_command(&bindgen)
        .args(["--target", "no-modules", "--no-typescript", "--out-dir"])
        .arg(&pkg)
        .arg(&wasm)
        .status()
        .with_context(|| format!("could not run {}", bindgen.display()))?;
    if !status.success() {
        bail!("wasm-bindgen failed ({status})");
    }
    let site = out.join("site");
    if site.exists() {
        std::fs::remove_dir_all(&site)
            .with_context(|| format!("cannot clear {}", site.display()))?;
    }
    std::fs::create_dir_all(&site).with_context(|| format!("cannot create {}", site.display()))?;
    let web = root.join("web");
    for entry in
        std::fs::read_dir(&web).with_context(|| format!("cannot read {}", web.display()))?
    {
        let path = entry?.path();
        let name = path.file_name().unwrap_or_default();
        let page_file = path
            .extension()
            .is_some_and(|e| e == "html" || e == "css" || e == "js");
        if path.is_file() && page_file {
            std::fs::copy(&path, site.join(name))
                .with_context(|| format!("cannot copy {}", path.display()))?;
        }
    }
    std::fs::copy(pkg.join("karman_web.js"), site.join("karman_web.js"))
        .context("cannot copy wasm-bindgen's karman_web.js")?;
    let module = std::fs::read(pkg.join("karman_web_bg.wasm")).context("cannot read the module")?;
    std::fs::write(
        site.join("karman_wasm.js"),
        format!(
            "// karman_web_bg.wasm ({} bytes), as base64: a page opened from disk cannot fetch it.\n\
             const KARMAN_WASM_BASE64 = \"{}\";\n",
            module.len(),
            base64(&module)
        ),
    )
    .context("cannot write karman_wasm.js")?;
    eprintln!(
        "xtask: the page is in {} (module {:.1} MB); serve that folder or open its index.html",
        site.display(),
        module.len() as f64 / 1e6
    );
    Ok(site)
}

/// Whether `CI` is set (and not empty).
fn in_ci() -> bool {
    std::env::var_os("CI").is_some_and(|v| !v.is_empty())
}

/// Runs `program args` in `dir`, failing on a non-zero exit.
fn run(program: &str, args: &[&str], dir: &Path) -> Result<()> {
    eprintln!("xtask: {program} {}", args.join(" "));
    let status = crate::child_command(program)
        .args(args)
        // apt without questions (CI has no terminal).
        .env("DEBIAN_FRONTEND", "noninteractive")
        .current_dir(dir)
        .status()
        .with_context(|| format!("could not run {program}"))?;
    if !status.success() {
        bail!("`{program} {}` failed ({status})", args.join(" "));
    }
    Ok(())
}

/// The browser test: the page built, the CLI it is compared with built, Chromium and
/// playwright-core made available, then `node web/test/browser.mjs`; with `native_timing`
/// (`web-test --native-timing`) the Calisto flight's native time is that of the page's own
/// call (`karman_web::fly`, the `fly_timing` example), else of the `karman simulate` process.
pub fn test(root: &Path, native_timing: bool) -> Result<()> {
    let chromium = Path::new("/usr/bin/chromium");
    if !chromium.exists() {
        if !in_ci() {
            eprintln!("xtask: web test skipped: no /usr/bin/chromium (apt-get install chromium)");
            return Ok(());
        }
        run("apt-get", &["install", "-y", "chromium"], root)
            .or_else(|_| {
                run("apt-get", &["update"], root)?;
                run("apt-get", &["install", "-y", "chromium"], root)
            })
            .context("CI is set: the browser test needs chromium")?;
    }
    if crate::child_command("node")
        .arg("--version")
        .output()
        .is_err()
    {
        if in_ci() {
            bail!("CI is set: the browser test needs node and npm");
        }
        eprintln!("xtask: web test skipped: no node");
        return Ok(());
    }
    let site = build(root)?;
    // The figures the page must match: the CLI's, the release build (its flight time too).
    // (In `ci` the validation step has built it already.)
    crate::cargo(root, &["build", "--release", "--package", "karman"])?;
    let karman = crate::target_dir(root).join("release/karman");
    // The native time of the page's very call: a build of its own (minutes), so only when
    // asked; otherwise the test times the whole `karman simulate` process.
    let timer = if native_timing {
        crate::cargo(
            root,
            &[
                "build",
                "--release",
                "--package",
                "karman-web",
                "--example",
                "fly_timing",
            ],
        )?;
        Some(crate::target_dir(root).join("release/examples/fly_timing"))
    } else {
        None
    };
    let tests = root.join("web/test");
    if !tests.join("node_modules/playwright-core").is_dir() {
        run("npm", &["ci", "--no-audit", "--no-fund"], &tests)?;
    }
    // This run's screenshots and downloads only.
    let shots = crate::target_dir(root).join("web/screenshots");
    if shots.exists() {
        std::fs::remove_dir_all(&shots)
            .with_context(|| format!("cannot clear {}", shots.display()))?;
    }
    std::fs::create_dir_all(&shots)?;
    let mut node = crate::child_command("node");
    if let Some(timer) = &timer {
        node.env("KARMAN_TIMER", timer);
    }
    let status = node
        .arg(tests.join("browser.mjs"))
        .env("KARMAN_SITE", &site)
        .env("KARMAN_CLI", &karman)
        .env("KARMAN_ROOT", root)
        .env("KARMAN_SCREENSHOTS", &shots)
        .env("KARMAN_CHROMIUM", chromium)
        .current_dir(&tests)
        .status()
        .context("could not run node")?;
    if !status.success() {
        bail!(
            "the browser test failed ({status}); screenshots in {}",
            shots.display()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #[test]
    fn base64_pads_the_last_group() {
        assert_eq!(super::base64(b""), "");
        assert_eq!(super::base64(b"f"), "Zg==");
        assert_eq!(super::base64(b"fo"), "Zm8=");
        assert_eq!(super::base64(b"foo"), "Zm9v");
        assert_eq!(super::base64(b"foobar\xff"), "Zm9vYmFy/w==");
    }
}
