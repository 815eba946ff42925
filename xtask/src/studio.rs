//! # `cargo xtask studio [--check]`: the browser studio
//!
//! Builds the studio into `target/studio/`: `crates/cdpr-studio` compiled in release for
//! `wasm32-unknown-unknown` (single-threaded: cdpr-workspace without `parallel`), wrapped by the
//! `wasm-bindgen` CLI (`--target web`: an ES module, no bundler), the page
//! (`crates/cdpr-studio/web/`), the shared renderer (`crates/cdpr/src/plot/viewer.js`) and the
//! shipped example robots (`examples/robots/*.toml`, listed in `robots/index.json`).
//!
//! `--check` then serves the folder from 127.0.0.1 (a small static server on a thread), opens
//! the page in headless Chromium for two robots (`--dump-dom` after a virtual-time budget),
//! reads the page's `<output id="cdpr-state">` and compares its lengths, tensions, feasibility
//! and method with `cdpr kinematics --json` and `cdpr tension --json` of the same build; the
//! page's `<output id="cdpr-errors">` must stay empty. It also checks that a bad pose gets a
//! message (not a script error), and saves `target/studio/screenshot.png`. Exit code 1 on a
//! mismatch, 2 on a usage error or a missing tool.
//!
//! Tools: the `wasm32-unknown-unknown` target (rustup), `wasm-bindgen` 0.2.130 (`$WASM_BINDGEN`,
//! `target/wasm-tools/bin/wasm-bindgen` or the PATH; `cargo install wasm-bindgen-cli --version
//! 0.2.130 --root target/wasm-tools`), Chromium (`$CDPR_CHROMIUM`, `chromium` or `chromium-browser`).

use serde_json::Value;
use std::io::{BufRead, BufReader, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

const HELP: &str = "cargo xtask studio [--check]: builds the browser studio into target/studio/ \
(wasm32-unknown-unknown release build of crates/cdpr-studio, wasm-bindgen --target web, the page \
and the example robots). --check also serves it from 127.0.0.1, loads it in headless Chromium for \
two robots and compares the page's state with the CLI's JSON, and writes \
target/studio/screenshot.png.";

/// The CLI the page is compared with is built with xtask's own profile (`cargo xtask` is a
/// release build; `cargo run -p xtask -- studio --check` a debug one).
const PROFILE: &[&str] = if cfg!(debug_assertions) {
    &[]
} else {
    &["--release"]
};

/// The wasm-bindgen CLI version the crate pins (`wasm-bindgen = \"=0.2.130\"`).
const WASM_BINDGEN_VERSION: &str = "0.2.130";

/// Runs `cargo xtask studio`.
pub fn run(root: &Path, args: &[String]) -> ExitCode {
    let mut check = false;
    for a in args {
        match a.as_str() {
            "--check" => check = true,
            "-h" | "--help" => {
                println!("{HELP}");
                return ExitCode::SUCCESS;
            }
            other => {
                eprintln!("error: unknown option `{other}`\n\n{HELP}");
                return ExitCode::from(2);
            }
        }
    }
    let out = root.join("target/studio");
    if let Err(e) = build(root, &out) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    println!("studio: {}", out.display());
    if !check {
        return ExitCode::SUCCESS;
    }
    match self::check(root, &out) {
        Ok(()) => {
            println!("studio check: ok");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("studio check failed: {e}");
            ExitCode::FAILURE
        }
    }
}

fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())
}

fn run_cmd(cmd: &mut Command) -> Result<Vec<u8>, String> {
    let o = cmd
        .output()
        .map_err(|e| format!("{:?}: {e}", cmd.get_program()))?;
    if !o.status.success() {
        return Err(format!(
            "{:?} {:?} failed ({}):\n{}",
            cmd.get_program(),
            cmd.get_args().collect::<Vec<_>>(),
            o.status,
            String::from_utf8_lossy(&o.stderr)
        ));
    }
    Ok(o.stdout)
}

fn wasm_bindgen(root: &Path) -> Result<PathBuf, String> {
    let candidates = std::env::var("WASM_BINDGEN")
        .ok()
        .map(PathBuf::from)
        .into_iter()
        .chain([root.join("target/wasm-tools/bin/wasm-bindgen")])
        .chain([PathBuf::from("wasm-bindgen")]);
    for c in candidates {
        if let Ok(o) = Command::new(&c).arg("--version").output()
            && o.status.success()
        {
            let v = String::from_utf8_lossy(&o.stdout);
            if !v.contains(WASM_BINDGEN_VERSION) {
                return Err(format!(
                    "{} is {}, the crate needs {WASM_BINDGEN_VERSION}: cargo install \
                     wasm-bindgen-cli --version {WASM_BINDGEN_VERSION} --root target/wasm-tools",
                    c.display(),
                    v.trim()
                ));
            }
            return Ok(c);
        }
    }
    Err(format!(
        "wasm-bindgen not found ($WASM_BINDGEN, target/wasm-tools/bin or PATH): cargo install \
         wasm-bindgen-cli --version {WASM_BINDGEN_VERSION} --root target/wasm-tools"
    ))
}

/// Builds the studio into `out`.
fn build(root: &Path, out: &Path) -> Result<(), String> {
    let bindgen = wasm_bindgen(root)?;
    // Release without debug info (the workspace's release profile keeps line tables for
    // profiling; the page does not need them).
    run_cmd(
        Command::new(cargo())
            .current_dir(root)
            .env("CARGO_PROFILE_RELEASE_DEBUG", "0")
            .args([
                "build",
                "--release",
                "-p",
                "cdpr-studio",
                "--target",
                "wasm32-unknown-unknown",
            ]),
    )?;
    let wasm = root.join("target/wasm32-unknown-unknown/release/cdpr_studio.wasm");
    if out.exists() {
        std::fs::remove_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    }
    std::fs::create_dir_all(out.join("robots")).map_err(|e| e.to_string())?;
    run_cmd(
        Command::new(&bindgen)
            .args(["--target", "web", "--no-typescript", "--out-dir"])
            .arg(out)
            .arg(&wasm),
    )?;
    let copy = |from: PathBuf, to: PathBuf| {
        std::fs::copy(&from, &to)
            .map(|_| ())
            .map_err(|e| format!("{} → {}: {e}", from.display(), to.display()))
    };
    let web = root.join("crates/cdpr-studio/web");
    for f in web_files(&web)? {
        copy(web.join(&f), out.join(&f))?;
    }
    copy(
        root.join("crates/cdpr/src/plot/viewer.js"),
        out.join("viewer.js"),
    )?;
    let mut names: Vec<String> = std::fs::read_dir(root.join("examples/robots"))
        .map_err(|e| e.to_string())?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    for n in &names {
        copy(
            root.join("examples/robots").join(n),
            out.join("robots").join(n),
        )?;
    }
    std::fs::write(
        out.join("robots/index.json"),
        serde_json::to_string(&names).expect("names serialise"),
    )
    .map_err(|e| e.to_string())?;
    report_size(out, &web);
    Ok(())
}

/// The page's files (`crates/cdpr-studio/web/`: the HTML, the style and the ES modules).
fn web_files(web: &Path) -> Result<Vec<String>, String> {
    let mut names: Vec<String> = std::fs::read_dir(web)
        .map_err(|e| format!("{}: {e}", web.display()))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| [".html", ".js", ".css"].iter().any(|x| n.ends_with(x)))
        .collect();
    names.sort();
    Ok(names)
}

/// Prints the first-load size (page, modules, glue, wasm; gzip -9 as a static host would serve
/// them).
fn report_size(out: &Path, web: &Path) {
    let mut files = web_files(web).unwrap_or_default();
    files.extend(["viewer.js", "cdpr_studio.js", "cdpr_studio_bg.wasm"].map(String::from));
    let (mut raw, mut gz) = (0u64, 0u64);
    for f in files {
        let p = out.join(f);
        raw += std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
        if let Ok(o) = Command::new("gzip").arg("-9c").arg(&p).output() {
            gz += o.stdout.len() as u64;
        }
    }
    println!(
        "studio first load: {:.2} MB, {:.2} MB gzip -9 (goal ≤ 3 MB compressed)",
        raw as f64 / 1e6,
        gz as f64 / 1e6
    );
}

// ---- the check -----------------------------------------------------------------------------

/// A static file server on 127.0.0.1 for `dir` (GET only), on a background thread.
fn serve(dir: PathBuf) -> Result<u16, String> {
    let listener = TcpListener::bind("127.0.0.1:0").map_err(|e| e.to_string())?;
    let port = listener.local_addr().map_err(|e| e.to_string())?.port();
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            let dir = dir.clone();
            std::thread::spawn(move || {
                let _ = respond(&dir, stream);
            });
        }
    });
    Ok(port)
}

fn respond(dir: &Path, mut stream: TcpStream) -> std::io::Result<()> {
    let mut line = String::new();
    let mut reader = BufReader::new(stream.try_clone()?);
    reader.read_line(&mut line)?;
    // Drain the headers.
    let mut h = String::new();
    while reader.read_line(&mut h)? > 2 {
        h.clear();
    }
    let path = line.split_whitespace().nth(1).unwrap_or("/");
    let path = path.split('?').next().unwrap_or("/");
    let rel = if path == "/" {
        "index.html"
    } else {
        path.trim_start_matches('/')
    };
    let file = dir.join(rel);
    let inside = !rel.split('/').any(|p| p == "..");
    match std::fs::read(&file) {
        Ok(body) if inside => {
            let ty = match file.extension().and_then(|e| e.to_str()) {
                Some("html") => "text/html; charset=utf-8",
                Some("js") => "text/javascript; charset=utf-8",
                Some("css") => "text/css; charset=utf-8",
                Some("wasm") => "application/wasm",
                Some("json") => "application/json",
                _ => "text/plain; charset=utf-8",
            };
            write!(
                stream,
                "HTTP/1.1 200 OK\r\nContent-Type: {ty}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                body.len()
            )?;
            stream.write_all(&body)
        }
        _ => write!(
            stream,
            "HTTP/1.1 404 Not Found\r\nContent-Length: 0\r\nConnection: close\r\n\r\n"
        ),
    }
}

fn chromium() -> Result<String, String> {
    if let Ok(b) = std::env::var("CDPR_CHROMIUM") {
        return Ok(b);
    }
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|b| {
            Command::new(b)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
        .map(String::from)
        .ok_or_else(|| "no Chromium (apt-get install chromium, or set CDPR_CHROMIUM)".into())
}

fn headless(browser: &str, url: &str, extra: &[&str]) -> Result<String, String> {
    let profile = std::env::temp_dir().join(format!("cdpr-studio-chromium-{}", std::process::id()));
    let out = run_cmd(
        Command::new(browser)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--no-first-run",
                "--hide-scrollbars",
                "--window-size=1400,860",
                "--virtual-time-budget=20000",
            ])
            .args(extra)
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg(url),
    )?;
    let _ = std::fs::remove_dir_all(&profile);
    Ok(String::from_utf8_lossy(&out).into_owned())
}

/// The text of `<output id="ID" …>…</output>` in a dumped DOM, unescaped.
fn output(dom: &str, id: &str) -> Option<String> {
    let start = dom.find(&format!("<output id=\"{id}\""))?;
    let open = start + dom[start..].find('>')? + 1;
    let close = open + dom[open..].find("</output>")?;
    Some(
        dom[open..close]
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&quot;", "\"")
            .replace("&nbsp;", "\u{a0}")
            .replace("&amp;", "&"),
    )
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .map(|a| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
        .unwrap_or_default()
}

/// |a − b| ≤ 1e-9 (1 + |b|) component by component.
fn close(what: &str, page: &Value, cli: &Value) -> Result<(), String> {
    let (a, b) = (numbers(page), numbers(cli));
    let agree = |x: &f64, y: &f64| (x - y).abs() <= 1e-9 * (1.0 + y.abs());
    if a.len() != b.len() || !a.iter().zip(&b).all(|(x, y)| agree(x, y)) {
        return Err(format!("{what}: page {a:?}, CLI {b:?}"));
    }
    Ok(())
}

/// The page at `query` (after `index.html?`): its state, once it is ready with no script error.
fn page_state(browser: &str, port: u16, query: &str) -> Result<Value, String> {
    let url = format!("http://127.0.0.1:{port}/index.html?{query}");
    let dom = headless(browser, &url, &["--dump-dom"])?;
    let errors = output(&dom, "cdpr-errors").ok_or("no <output id=\"cdpr-errors\"> in the page")?;
    if !errors.trim().is_empty() {
        return Err(format!("{query}: script errors in the page:\n{errors}"));
    }
    let text = output(&dom, "cdpr-state").ok_or("no <output id=\"cdpr-state\"> in the page")?;
    let state: Value =
        serde_json::from_str(&text).map_err(|e| format!("{query}: state `{text}`: {e}"))?;
    if state["ready"] != Value::Bool(true) {
        return Err(format!("{query}: the page did not finish: {state}"));
    }
    // The method's reference is on the method list's hover (its title) and in the state.
    let reference = state["method_reference"].as_str().unwrap_or_default();
    let title = format!(
        "id=\"method\" title=\"{}\"",
        reference.replace('&', "&amp;")
    );
    if state.get("error").is_none() && (reference.is_empty() || !dom.contains(&title)) {
        return Err(format!(
            "{query}: the method list's hover does not show the method's reference `{reference}`"
        ));
    }
    Ok(state)
}

/// `cdpr CMD ROBOT ARGS… --json` of the same build.
fn cli_json(root: &Path, robot: &str, cmd: &str, args: &[String]) -> Result<Value, String> {
    let out = run_cmd(
        Command::new(cargo())
            .current_dir(root)
            .args(["run", "-q", "-p", "cdpr"])
            .args(PROFILE)
            .arg("--")
            .arg(cmd)
            .arg(root.join("examples/robots").join(robot))
            .args(args)
            .arg("--json"),
    )?;
    serde_json::from_slice(&out).map_err(|e| format!("cdpr {cmd} {args:?} --json: {e}"))
}

/// Comma-separated numbers, each written exactly (shortest round-trip form).
fn csv(v: &Value) -> String {
    numbers(v)
        .iter()
        .map(f64::to_string)
        .collect::<Vec<_>>()
        .join(",")
}

/// The tension method and the external wrench of one check.
struct Load<'a> {
    method: &'a str,
    wrench: &'a str,
}

impl Load<'_> {
    fn args(&self) -> Vec<String> {
        let mut a = vec![format!("--method={}", self.method)];
        if !self.wrench.is_empty() {
            a.push(format!("--wrench={}", self.wrench));
        }
        a
    }
}

/// The page's state at its pose against `cdpr kinematics` and `cdpr tension` at that pose.
fn compare_state(root: &Path, robot: &str, state: &Value, load: &Load) -> Result<(), String> {
    if let Some(e) = state.get("error") {
        return Err(format!("{robot}: the page reports {e}"));
    }
    let pose = format!("--pose={}", csv(&state["pose"]));
    let kin = cli_json(root, robot, "kinematics", std::slice::from_ref(&pose))?;
    let mut args = load.args();
    args.push(pose);
    let ten = cli_json(root, robot, "tension", &args)?;
    close(&format!("{robot}: pose"), &state["pose"], &ten["pose"])?;
    close(
        &format!("{robot}: lengths (m)"),
        &state["lengths"],
        &kin["lengths"],
    )?;
    close(
        &format!("{robot}: tensions (N)"),
        &state["tensions"],
        &ten["tensions"],
    )?;
    close(
        &format!("{robot}: external wrench"),
        &state["external_wrench"],
        &ten["external_wrench"],
    )?;
    for key in ["feasible", "method", "robot", "reason"] {
        if state[key] != ten[key] {
            return Err(format!(
                "{robot}: {key}: page {}, CLI {}",
                state[key], ten[key]
            ));
        }
    }
    Ok(())
}

/// One robot at a pose: the page's state against the CLI's.
fn check_robot(
    root: &Path,
    browser: &str,
    port: u16,
    robot: &str,
    pose: &str,
    load: &Load,
) -> Result<Value, String> {
    let query = format!(
        "robot=robots/{robot}&pose={pose}&method={}&wrench={}",
        load.method, load.wrench
    );
    let state = page_state(browser, port, &query)?;
    compare_state(root, robot, &state, load)?;
    println!(
        "studio check: {robot} at ({pose}), {}: {} lengths and tensions equal the CLI's; \
         feasible {}; pose update {:.2} ms",
        load.method,
        numbers(&state["lengths"]).len(),
        state["feasible"],
        state["timing_ms"]["pose_update"]
            .as_f64()
            .unwrap_or(f64::NAN)
    );
    Ok(state)
}

/// A mouse drag of the platform by (dx, dy) px (`mode`: "" for the view plane, or x, y, z):
/// the pose moved, by hand, as the orthographic view says, and the state there is the CLI's.
fn check_drag(
    root: &Path,
    browser: &str,
    port: u16,
    robot: &str,
    (pose, dx, dy, mode): (&str, f64, f64, &str),
    load: &Load,
) -> Result<(), String> {
    let query = format!(
        "robot=robots/{robot}&pose={pose}&method={}&drag={dx},{dy},{mode}",
        load.method
    );
    let state = page_state(browser, port, &query)?;
    compare_state(root, robot, &state, load)?;
    let drag = &state["drag"];
    let (from, to) = (numbers(&drag["from"]), numbers(&drag["to"]));
    let d: Vec<f64> = (0..3)
        .map(|k| to.get(k).unwrap_or(&0.0) - from[k])
        .collect();
    let v = &drag["view"];
    let (yaw, pitch, scale) = (
        v["yaw"].as_f64().unwrap_or(f64::NAN),
        v["pitch"].as_f64().unwrap_or(f64::NAN),
        v["scale"].as_f64().unwrap_or(f64::NAN),
    );
    // The view's screen axes in the world (toView's rows): right, up and the line of sight.
    let (cy, sy, ce, se) = (yaw.cos(), yaw.sin(), pitch.cos(), pitch.sin());
    let right = [cy, -sy, 0.0];
    let up = [sy * se, cy * se, ce];
    let depth = [-sy * ce, -cy * ce, se];
    let dot = |a: &[f64; 3]| a.iter().zip(&d).map(|(x, y)| x * y).sum::<f64>();
    let planar = matches!(state["motion"].as_str(), Some("planar" | "point2"));
    let screen = [dot(&right) * scale, -dot(&up) * scale];
    let tol = 1e-6 * (1.0 + dx.abs() + dy.abs());
    let ok = match mode {
        // Along one axis: only that coordinate moves, by the mouse motion's projection on the
        // axis' screen image (least squares), so the residual is normal to that image.
        "x" | "y" | "z" => {
            let k = "xyz".find(mode).unwrap_or(0);
            let (ax, ay) = (right[k], up[k]);
            let along = (dx * ax - dy * ay) / (ax * ax + ay * ay) / scale;
            (0..3).all(|j| j == k || d[j] == 0.0) && (d[k] - along).abs() <= tol / scale
        }
        _ => {
            let in_view = (screen[0] - dx).abs() <= tol && (screen[1] - dy).abs() <= tol;
            in_view
                && if planar {
                    d[2] == 0.0
                } else {
                    dot(&depth).abs() <= 1e-9
                }
        }
    };
    if !ok {
        return Err(format!(
            "{robot}: a drag of ({dx}, {dy}) px {mode} moved the platform by {d:?} m (screen \
             image {screen:?} px at {scale} px/m)"
        ));
    }
    println!(
        "studio check: {robot}: a drag of ({dx}, {dy}) px{} moved the platform by ({:.4}, {:.4}, \
         {:.4}) m as the view projects it; the state there equals the CLI's",
        if mode.is_empty() {
            String::new()
        } else {
            format!(" along {mode}")
        },
        d[0],
        d[1],
        d[2]
    );
    Ok(())
}
/// Where the workspace and path checks run (the 8-cable robot at [`CASE_POSE`], l2, no load):
/// the repository, the browser and the page's server.
struct Case<'a> {
    root: &'a Path,
    browser: &'a str,
    port: u16,
}

const CASE_ROBOT: &str = "ipanema-like-8.toml";
const CASE_POSE: &str = "0.3,0.2,1.1,0.05,-0.03,0.1";

impl Case<'_> {
    /// The page at the case's pose (l2, no extra load) with `extra` in the query.
    fn page(&self, extra: &str) -> Result<Value, String> {
        let query = format!("robot=robots/{CASE_ROBOT}&pose={CASE_POSE}&method=l2&{extra}");
        page_state(self.browser, self.port, &query)
    }

    /// `cdpr workspace` at the case's orientation and method with `extra` arguments.
    fn workspace(&self, extra: &[&str]) -> Result<Value, String> {
        let mut args = vec![
            "--method=l2".to_string(),
            "--orientation=0.05,-0.03,0.1".into(),
        ];
        args.extend(extra.iter().map(|a| a.to_string()));
        cli_json(self.root, CASE_ROBOT, "workspace", &args)
    }
}

/// Two scalars agree to 1e-9 relative.
fn close_scalar(what: &str, page: &Value, cli: &Value) -> Result<(), String> {
    close(what, &json_list(page), &json_list(cli))
}

/// The grid points at resolution 10 against `cdpr workspace --grid 10`.
fn check_grid(c: &Case) -> Result<(), String> {
    let page = c.page("grid=10")?;
    let cli = c.workspace(&["--grid=10"])?;
    let g = &page["grid"];
    for key in ["feasible_points", "total_points", "criteria", "dimension"] {
        if g[key] != cli[key] {
            return Err(format!("grid: {key}: page {}, CLI {}", g[key], cli[key]));
        }
    }
    close_scalar("grid: area (m³)", &g["area"], &cli["area"])?;
    close_scalar(
        "grid: points measure (m³)",
        &g["area_points"],
        &cli["area_points"],
    )?;
    println!(
        "studio check: {CASE_ROBOT} grid 10: {} of {} points feasible, {} m³, as `cdpr \
         workspace --grid 10`",
        g["feasible_points"], g["total_points"], g["area"]
    );
    Ok(())
}

/// The boundary mesh at grid 12 against `cdpr workspace --boundary mesh --grid 12`.
fn check_mesh(c: &Case) -> Result<(), String> {
    let page = c.page("mesh=12")?;
    let cli = c.workspace(&["--grid=12", "--boundary=mesh"])?;
    let m = &page["workspace"];
    close_scalar("mesh: volume (m³)", &m["volume_m3"], &cli["volume"])?;
    close_scalar(
        "mesh: grid volume (m³)",
        &m["grid_volume_m3"],
        &cli["grid_volume"],
    )?;
    let triangles = cli["triangles"].as_array().map_or(0, Vec::len);
    if m["triangles"] != triangles || m["criteria"] != cli["criteria"] {
        return Err(format!(
            "mesh: page {m}, CLI {triangles} triangles, criteria {}",
            cli["criteria"]
        ));
    }
    println!(
        "studio check: {CASE_ROBOT} mesh grid 12: volume {} m³, {} triangles, as `cdpr \
         workspace --boundary mesh --grid 12`",
        m["volume_m3"], m["triangles"]
    );
    Ok(())
}

/// The section z = 1.1 m (seeds: grid 20, chord 0.02 m) against `cdpr workspace --section`.
fn check_section(c: &Case) -> Result<(), String> {
    let page = c.page("section=z=1.1&chord=0.02")?;
    let cli = c.workspace(&["--grid=20", "--section=z=1.1", "--chord=0.02"])?;
    let sec = &page["section"];
    close_scalar("section: area (m²)", &sec["area"], &cli["area"])?;
    close(
        "section: signed areas (m²)",
        &sec["signed_areas"],
        &cli["signed_areas"],
    )?;
    println!(
        "studio check: {CASE_ROBOT} section z = 1.1 m: area {} m², {} boundary polygon(s), as \
         `cdpr workspace --section z=1.1`",
        sec["area"], sec["loops"]
    );
    Ok(())
}

/// Every sample's poses and tensions (N), and the motor torques (N·m), page against CLI.
fn same_samples(what: &str, path: &Value, cli: &Value) -> Result<usize, String> {
    let poses = path["poses"].as_array().cloned().unwrap_or_default();
    let cli_poses = cli["poses"].as_array().cloned().unwrap_or_default();
    if poses.len() != cli_poses.len() || poses.is_empty() {
        return Err(format!(
            "{what}: {} samples, CLI {}",
            poses.len(),
            cli_poses.len()
        ));
    }
    for k in 0..poses.len() {
        close(&format!("{what}: pose {k}"), &poses[k], &cli_poses[k])?;
        let (a, b) = (&path["tensions"][k], &cli["tensions"][k]);
        if a.is_null() != b.is_null() {
            return Err(format!("{what}: sample {k}: page {a}, CLI {b}"));
        }
        if !a.is_null() {
            close(&format!("{what}: tensions at sample {k} (N)"), a, b)?;
        }
    }
    let torques = &cli["drive_train"]["motor_torques"];
    if path["motor_torques"].is_null() != torques.is_null() {
        return Err(format!("{what}: motor torques on one side only"));
    }
    Ok(poses.len())
}

/// A path of 20 steps and a quintic trajectory of 2 s: the page's samples are `cdpr
/// trajectory`'s; the untimed path's positions are the straight line's and its tensions `cdpr
/// tension`'s at three of them.
fn check_path(c: &Case) -> Result<(), String> {
    let to = "0.5,0.4,1.2,0,0,0";
    let page = c.page(&format!("path={to}&steps=20"))?;
    let path = &page["path"];
    let segment = [
        format!("--from={CASE_POSE}"),
        format!("--to={to}"),
        "--method=l2".into(),
    ];
    let mut args = segment.to_vec();
    args.push("--samples=21".into());
    let cli = cli_json(c.root, CASE_ROBOT, "trajectory", &args)?;
    same_samples("path", path, &cli)?;
    let poses = path["poses"].as_array().cloned().unwrap_or_default();
    for k in [0, 7, 20] {
        let args = [
            "--method=l2".to_string(),
            format!("--pose={}", csv(&poses[k])),
        ];
        let ten = cli_json(c.root, CASE_ROBOT, "tension", &args)?;
        close(&format!("path: pose {k}"), &poses[k], &ten["pose"])?;
        close(
            &format!("path: tensions at pose {k} (N)"),
            &path["tensions"][k],
            &ten["tensions"],
        )?;
    }
    // The segment: the position moves on the straight line, p_k = p_0 + (p_1 − p_0) k / 20
    // (the orientation along the shortest rotation, slerp).
    let (from, end) = (numbers(&path["from"]), numbers(&path["to"]));
    let expect: Vec<f64> = (0..3)
        .map(|i| from[i] + (end[i] - from[i]) * 7.0 / 20.0)
        .collect();
    let position = Value::from(numbers(&poses[7])[..3].to_vec());
    close(
        "path: position 7 (m)",
        &position,
        &serde_json::json!(expect),
    )?;
    let page = c.page(&format!("path={to}&law=quintic&duration=2&dt=0.1"))?;
    let mut args = segment.to_vec();
    args.extend(
        [
            "--time-law=quintic",
            "--duration=2",
            "--dt=0.1",
            "--dynamics",
        ]
        .map(String::from),
    );
    let cli = cli_json(c.root, CASE_ROBOT, "trajectory", &args)?;
    let n = same_samples("trajectory", &page["path"], &cli)?;
    close("trajectory: t (s)", &page["path"]["x"], &cli["t"])?;
    println!(
        "studio check: {CASE_ROBOT}: a path of 21 poses and a quintic trajectory of {n} samples \
         (2 s, inertia balanced) equal `cdpr trajectory`'s; the path's tensions at poses 0, 7, 20 \
         equal `cdpr tension`'s"
    );
    Ok(())
}

fn json_list(v: &Value) -> Value {
    Value::Array(vec![v.clone()])
}

/// A bad pose is a message for the user, not a script error.
fn check_bad_pose(browser: &str, port: u16) -> Result<(), String> {
    let url = format!("http://127.0.0.1:{port}/index.html?robot=robots/tdpm-4.toml&pose=0,0");
    let dom = headless(browser, &url, &["--dump-dom"])?;
    let state: Value = serde_json::from_str(&output(&dom, "cdpr-state").unwrap_or_default())
        .map_err(|e| format!("bad-pose page: {e}"))?;
    let message = state["error"].as_str().unwrap_or_default();
    if !message.contains('3') || !output(&dom, "cdpr-errors").unwrap_or_default().is_empty() {
        return Err(format!(
            "bad pose: expected a message naming 3 coordinates, got {state}"
        ));
    }
    println!("studio check: a 2-number pose for a planar robot says: {message}");
    Ok(())
}

/// The screenshot: the 8-cable robot with its workspace mesh (grid 30), a section and a path.
fn screenshot(browser: &str, port: u16, out: &Path) -> Result<(), String> {
    let shot = out.join("screenshot.png");
    let url = format!(
        "http://127.0.0.1:{port}/index.html?robot=robots/ipanema-like-8.toml&method=l2&mesh=30\
         &section=z=1.1&path=0.5,0.4,1.2,0,0,0&steps=40"
    );
    let dom = headless(browser, &url, &["--dump-dom"])?;
    let state: Value = serde_json::from_str(&output(&dom, "cdpr-state").unwrap_or_default())
        .map_err(|e| format!("mesh page: {e}"))?;
    println!(
        "studio check: workspace mesh grid 30 in the page: {:.0} ms, volume {} m³; first state {:.0} ms",
        state["timing_ms"]["mesh"].as_f64().unwrap_or(f64::NAN),
        state["workspace"]["volume_m3"],
        state["timing_ms"]["first_state"]
            .as_f64()
            .unwrap_or(f64::NAN)
    );
    headless(
        browser,
        &url,
        &[&format!("--screenshot={}", shot.display())],
    )?;
    if !std::fs::read(&shot).is_ok_and(|b| b.starts_with(b"\x89PNG")) {
        return Err(format!("{}: no screenshot", shot.display()));
    }
    println!("studio check: screenshot {}", shot.display());
    Ok(())
}

fn check(root: &Path, out: &Path) -> Result<(), String> {
    let browser = chromium()?;
    let port = serve(out.to_path_buf())?;
    // A spatial 8-cable robot with a load, and the thesis' planar 4-cable robot.
    let (spatial, planar) = ("ipanema-like-8.toml", "tdpm-4.toml");
    let l2 = Load {
        method: "l2",
        wrench: "",
    };
    let loaded = Load {
        method: "l2",
        wrench: "0,0,-50,0,0,0",
    };
    let linf = Load {
        method: "linf",
        wrench: "0,-10,0",
    };
    check_robot(
        root,
        &browser,
        port,
        spatial,
        "0.3,0.2,1.1,0.05,-0.03,0.1",
        &loaded,
    )?;
    check_robot(root, &browser, port, planar, "0.1,-0.05,0.2", &linf)?;
    // Dragging the platform: in the view plane, along z, and in the plane of a planar robot.
    let start = "0.3,0.2,1.1,0.05,-0.03,0.1";
    check_drag(root, &browser, port, spatial, (start, 40.0, -25.0, ""), &l2)?;
    check_drag(
        root,
        &browser,
        port,
        spatial,
        (start, 10.0, -30.0, "z"),
        &l2,
    )?;
    check_drag(
        root,
        &browser,
        port,
        planar,
        ("0.1,-0.05,0.2", 30.0, 10.0, ""),
        &l2,
    )?;
    let case = Case {
        root,
        browser: &browser,
        port,
    };
    check_grid(&case)?;
    check_mesh(&case)?;
    check_section(&case)?;
    check_path(&case)?;
    check_bad_pose(&browser, port)?;
    screenshot(&browser, port, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_read_and_unescaped() {
        let dom = r#"<p>x</p><output id="cdpr-state" hidden="">{"a":"&lt;b&gt; &amp; c"}</output>"#;
        assert_eq!(output(dom, "cdpr-state").unwrap(), r#"{"a":"<b> & c"}"#);
        assert!(output(dom, "cdpr-errors").is_none());
    }

    #[test]
    fn numbers_must_agree_to_1e9() {
        let a = serde_json::json!([1.0, 2.0]);
        assert!(close("x", &a, &serde_json::json!([1.0, 2.0 + 1e-12])).is_ok());
        assert!(close("x", &a, &serde_json::json!([1.0, 2.001])).is_err());
        assert!(close("x", &a, &serde_json::json!([1.0])).is_err());
        assert!(close("x", &serde_json::json!(null), &serde_json::json!([1.0])).is_err());
    }
}
