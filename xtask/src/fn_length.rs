//! # Long functions in the front ends
//!
//! `cargo xtask fn-length [MAX] [DIR …]` lists the functions longer than MAX lines (default
//! [`MAX_LINES`]) in the Rust files under the front-end directories ([`FRONT_ENDS`]: the command
//! line and plots, the Python package, the studio) and exits with code 1 if there is one. A
//! function runs from its `fn` line to the line where its braces balance again (line count
//! inclusive); braces inside string and character literals and after `//` are not counted,
//! and a declaration without a body (`fn f();`) is skipped. The rule is the project's "no
//! front-end function over ~80 lines" (docs/architecture.md); the test below runs it over the
//! tree under `cargo test`.

use std::fs;
use std::path::{Path, PathBuf};

/// The longest function the front ends may have (lines, signature to closing brace).
pub const MAX_LINES: usize = 80;

/// The front-end directories, relative to the repository root.
pub const FRONT_ENDS: [&str; 3] = ["crates/cdpr/src", "python/src", "crates/cdpr-studio/src"];

/// A function longer than the limit.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LongFunction {
    pub file: PathBuf,
    /// 1-based line of its `fn`.
    pub line: usize,
    pub name: String,
    /// Its length in lines.
    pub lines: usize,
}

/// The name of the function declared on `line`, if the line starts (after visibility and
/// qualifiers: `pub`, `pub(crate)`, `const`, `async`, `unsafe`, `extern "C"`) with `fn NAME`.
fn fn_name(line: &str) -> Option<&str> {
    let mut rest = line.trim_start();
    loop {
        if let Some(r) = rest.strip_prefix("pub(") {
            rest = r.split_once(')')?.1.trim_start();
        } else if let Some(r) = ["pub ", "const ", "async ", "unsafe "]
            .iter()
            .find_map(|q| rest.strip_prefix(q))
        {
            rest = r.trim_start();
        } else if let Some(r) = rest.strip_prefix("extern ") {
            let r = r.trim_start();
            rest = match r.strip_prefix('"') {
                Some(abi) => abi.split_once('"')?.1.trim_start(),
                None => r,
            };
        } else {
            break;
        }
    }
    let rest = rest.strip_prefix("fn ")?.trim_start();
    let end = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    (end > 0).then(|| &rest[..end])
}

/// The braces of one line that count: string literals `"…"` (with escapes) and character
/// literals `'x'`, `'\n'` blanked, everything after `//` dropped. Returns (opening, closing).
fn braces(line: &str) -> (usize, usize) {
    let chars: Vec<char> = line.chars().collect();
    let (mut open, mut close) = (0, 0);
    let mut i = 0;
    while i < chars.len() {
        match chars[i] {
            '"' => {
                // To the closing quote; an unterminated string runs to the end of the line.
                i += 1;
                while i < chars.len() && chars[i] != '"' {
                    i += if chars[i] == '\\' { 2 } else { 1 };
                }
            }
            '\'' if chars.get(i + 1) == Some(&'\\') && chars.get(i + 3) == Some(&'\'') => i += 3,
            '\'' if chars.get(i + 2) == Some(&'\'') && chars.get(i + 1) != Some(&'\\') => i += 2,
            '/' if chars.get(i + 1) == Some(&'/') => break,
            '{' => open += 1,
            '}' => close += 1,
            _ => {}
        }
        i += 1;
    }
    (open, close)
}

/// The functions of one source longer than `max` lines, in order.
pub fn long_functions(src: &str, max: usize) -> Vec<(usize, String, usize)> {
    let lines: Vec<&str> = src.split('\n').collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let Some(name) = fn_name(lines[i]).filter(|_| !lines[i].trim_end().ends_with(';')) else {
            i += 1;
            continue;
        };
        let (mut depth, mut started, mut j) = (0i64, false, i);
        while j < lines.len() {
            let (open, close) = braces(lines[j]);
            depth += open as i64 - close as i64;
            started |= open > 0;
            if started && depth <= 0 {
                break;
            }
            j += 1;
        }
        let n = j.min(lines.len() - 1) - i + 1;
        if n > max {
            out.push((i + 1, name.to_string(), n));
        }
        i = if started { j + 1 } else { i + 1 };
    }
    out
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The functions longer than `max` lines in the Rust files under `dirs` (relative to `root`).
pub fn find(root: &Path, dirs: &[&str], max: usize) -> Vec<LongFunction> {
    let mut files = Vec::new();
    for d in dirs {
        rust_files(&root.join(d), &mut files);
    }
    let mut out = Vec::new();
    for file in files {
        let Ok(src) = fs::read_to_string(&file) else {
            continue;
        };
        for (line, name, lines) in long_functions(&src, max) {
            out.push(LongFunction {
                file: file.strip_prefix(root).unwrap_or(&file).to_path_buf(),
                line,
                name,
                lines,
            });
        }
    }
    out
}

/// `cargo xtask fn-length [MAX] [DIR …]`.
pub fn run(root: &Path, args: &[String]) -> Result<(), String> {
    if args.iter().any(|a| a == "-h" || a == "--help") {
        println!(
            "cargo xtask fn-length [MAX] [DIR …]: the functions longer than MAX lines (default {MAX_LINES}) under DIR (default the front ends: {}); exit code 1 if any",
            FRONT_ENDS.join(", ")
        );
        return Ok(());
    }
    let (max, dirs) = match args.first().map(|a| a.parse::<usize>()) {
        Some(Ok(m)) => (m, &args[1..]),
        Some(Err(_)) if args[0].starts_with('-') => {
            return Err(format!("unknown option `{}` (see --help)", args[0]));
        }
        _ => (MAX_LINES, args),
    };
    let dirs: Vec<&str> = if dirs.is_empty() {
        FRONT_ENDS.to_vec()
    } else {
        dirs.iter().map(String::as_str).collect()
    };
    let long = find(root, &dirs, max);
    for f in &long {
        println!("{:4} {}:{} {}", f.lines, f.file.display(), f.line, f.name);
    }
    if long.is_empty() {
        println!("no function over {max} lines in {}", dirs.join(", "));
        Ok(())
    } else {
        Err(format!("{} function(s) over {max} lines", long.len()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A function of `body` lines between its signature and closing brace.
    fn function(name: &str, body: usize) -> String {
        let mut s = format!("pub(crate) fn {name}() {{\n");
        for k in 0..body {
            s += &format!("    let _x{k} = 1;\n");
        }
        s + "}\n"
    }

    #[test]
    fn lengths_count_from_the_signature_to_the_closing_brace() {
        // 3 + 78 lines = 81 > 80; 80 lines is allowed.
        let src = function("long", 79) + &function("exact", 78) + "fn decl();\n";
        assert_eq!(long_functions(&src, 80), [(1, "long".to_string(), 81)]);
        assert_eq!(long_functions(&src, 79).len(), 2);
    }

    #[test]
    fn braces_in_strings_characters_and_comments_do_not_count() {
        let src = "fn f() {\n    let s = \"}}}\\\"}\";\n    let c = '}';\n    let e = '\\'';\n    // }\n    g();\n}\nfn h() {\n}\n";
        assert_eq!(long_functions(src, 0)[0], (1, "f".to_string(), 7));
        assert_eq!(long_functions(src, 0)[1], (8, "h".to_string(), 2));
        assert_eq!(braces("let c = '{'; // {"), (0, 0));
        assert_eq!(braces("x.map(|a| { a }) 'a: loop {"), (2, 1));
    }

    #[test]
    fn qualifiers_are_read_and_other_lines_are_not_functions() {
        assert_eq!(
            fn_name("    pub(crate) const unsafe fn go<T>()"),
            Some("go")
        );
        assert_eq!(fn_name("extern \"C\" fn cb(x: i32) {"), Some("cb"));
        assert_eq!(fn_name("pub async fn run() {"), Some("run"));
        assert_eq!(fn_name("let f = |x| x; // fn g"), None);
        assert_eq!(fn_name("fnord();"), None);
        // A signature over several lines, the brace on a later line.
        let src = "fn g(\n    a: u8,\n) -> u8\n{\n    a\n}\n";
        assert_eq!(long_functions(src, 0), [(1, "g".to_string(), 6)]);
    }

    /// The rule itself: no front-end function over [`MAX_LINES`] lines.
    #[test]
    fn no_front_end_function_is_over_the_limit() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let long = find(&root, &FRONT_ENDS, MAX_LINES);
        assert!(
            long.is_empty(),
            "split these functions into named steps (at most {MAX_LINES} lines each):\n{}",
            long.iter()
                .map(|f| format!("{:4} {}:{} {}", f.lines, f.file.display(), f.line, f.name))
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}
