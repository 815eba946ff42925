//! # Import loops: files that use each other
//!
//! `cargo xtask loops` reads every Rust crate of the tree (the Cargo workspace, `python/`, `fuzz/`,
//! `benches/`), follows each crate's module tree from its roots (`src/lib.rs`, `src/main.rs`,
//! `src/bin/*.rs`, `tests/*.rs`, `tests/*/main.rs`, `benches/*.rs`, `examples/*.rs`,
//! `fuzz_targets/*.rs`; `mod x;` declarations, `#[path = "…"]` honoured) and records which file names
//! which: every path starting with `crate::`, `super::` or `self::`, in `use` trees (groups
//! included) and in expressions, types and macro arguments alike (comments and string literals
//! are skipped). A path names the file of the longest module prefix it resolves to.
//!
//! A file's ancestors and descendants in the module tree are its context, not its peers: a child
//! using a helper of its parent (`super::load_robot`) and a parent dispatching to its children
//! (`tension::run`) are the module tree itself. Every other reference is an edge between peers,
//! and a strongly connected component of two or more files in that graph is an import loop
//! (`use super::b` in `a.rs` while `b.rs` uses `a.rs`): the command prints each loop with the lines
//! that close it and exits with code 1. The test below runs it over the tree under `cargo test`.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// A reference from one file to a peer file: the line where it is made.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Edge {
    pub from: PathBuf,
    pub to: PathBuf,
    pub line: usize,
    /// Made in test code (a `#[cfg(test)]` module): a test checking one method against another.
    pub test: bool,
}

/// A set of files that import each other in a loop, with the references between them.
#[derive(Debug)]
pub struct Loop {
    pub files: Vec<PathBuf>,
    pub edges: Vec<Edge>,
}

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Ident(String),
    PathSep,
    Punct(char),
}

/// The tokens of a Rust source with their line numbers: identifiers, `::` and single punctuation;
/// comments, string, byte-string, raw-string and character literals, lifetimes and numbers dropped.
fn tokenize(src: &str) -> Vec<(Token, usize)> {
    let chars: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    let n = chars.len();
    let at = |k: usize| chars.get(k).copied().unwrap_or('\0');
    while i < n {
        let c = chars[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && at(i + 1) == '/' {
            while i < n && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < n {
                if chars[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if chars[i] == '\n' {
                        line += 1;
                    }
                    i += 1;
                }
            }
        } else if (c == 'r' || (c == 'b' && at(i + 1) == 'r'))
            && matches!(at(i + 1 + usize::from(c == 'b')), '"' | '#')
            && raw_string_start(&chars, i + 1 + usize::from(c == 'b')).is_some()
        {
            let start = i + 1 + usize::from(c == 'b');
            let hashes = raw_string_start(&chars, start).unwrap_or(0);
            i = start + hashes + 1;
            while i < n {
                if chars[i] == '"' && (0..hashes).all(|h| at(i + 1 + h) == '#') {
                    i += 1 + hashes;
                    break;
                }
                if chars[i] == '\n' {
                    line += 1;
                }
                i += 1;
            }
        } else if c == '"' || (c == 'b' && at(i + 1) == '"') {
            i += if c == 'b' { 2 } else { 1 };
            while i < n && chars[i] != '"' {
                if chars[i] == '\\' {
                    i += 1;
                }
                if at(i) == '\n' {
                    line += 1;
                }
                i += 1;
            }
            i += 1;
        } else if c == '\'' || (c == 'b' && at(i + 1) == '\'') {
            let q = if c == 'b' { i + 1 } else { i };
            if at(q + 1) == '\\' {
                // an escaped character literal: past the escaped character, up to the closing quote
                i = q + 3;
                while i < n && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if at(q + 2) == '\'' {
                i = q + 3;
            } else {
                // a lifetime or label: skip the quote, its name is an identifier of no interest
                i = q + 1;
                while i < n && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
            }
        } else if c.is_ascii_digit() {
            while i < n && (chars[i].is_alphanumeric() || chars[i] == '_' || chars[i] == '.') {
                if chars[i] == '.' && !at(i + 1).is_ascii_digit() {
                    break;
                }
                i += 1;
            }
        } else if c.is_alphabetic() || c == '_' {
            let s = i;
            while i < n && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let word: String = chars[s..i].iter().collect();
            let word = word.strip_prefix("r#").map(str::to_owned).unwrap_or(word);
            out.push((Token::Ident(word), line));
        } else if c == ':' && at(i + 1) == ':' {
            out.push((Token::PathSep, line));
            i += 2;
        } else {
            out.push((Token::Punct(c), line));
            i += 1;
        }
    }
    out
}

/// At `chars[k]` (after `r` or `br`): `Some(number of #)` if a raw string starts here.
fn raw_string_start(chars: &[char], k: usize) -> Option<usize> {
    let mut h = 0;
    while chars.get(k + h) == Some(&'#') {
        h += 1;
    }
    (chars.get(k + h) == Some(&'"')).then_some(h)
}

/// The paths of one path or `use` tree starting at `tokens[i]` (after `prefix`): every full path
/// (groups expanded) and the index after it.
fn parse_tree(
    tokens: &[(Token, usize)],
    mut i: usize,
    prefix: Vec<String>,
) -> (Vec<Vec<String>>, usize) {
    let mut path = prefix;
    loop {
        match tokens.get(i).map(|t| &t.0) {
            Some(Token::Ident(name)) => {
                if name != "self" || path.is_empty() {
                    path.push(name.clone());
                }
                i += 1;
                if tokens.get(i).map(|t| &t.0) == Some(&Token::PathSep) {
                    i += 1;
                    continue;
                }
                return (vec![path], i);
            }
            Some(Token::Punct('{')) => {
                i += 1;
                let mut all = Vec::new();
                loop {
                    match tokens.get(i).map(|t| &t.0) {
                        Some(Token::Punct('}')) | None => return (all, i + 1),
                        Some(Token::Punct(',')) => i += 1,
                        _ => {
                            let start = i;
                            let (paths, next) = parse_tree(tokens, i, path.clone());
                            all.extend(paths);
                            // `as name` and anything unexpected: skip to the next item
                            i = next.max(start + 1);
                            while !matches!(
                                tokens.get(i).map(|t| &t.0),
                                Some(Token::Punct(',' | '}')) | None
                            ) {
                                i += 1;
                            }
                        }
                    }
                }
            }
            Some(Token::Punct('*')) => return (vec![path], i + 1),
            _ => return (vec![path], i),
        }
    }
}

/// One file of a crate: its module path and where its `mod` declarations point.
struct ModuleFile {
    path: PathBuf,
    module: Vec<String>,
    /// Declared under `#[cfg(test)]` (itself or an ancestor).
    test: bool,
}

/// Whether the tokens just before `tokens[k]` (a `mod`, after an optional `pub`) are `#[cfg(test)]`.
fn after_cfg_test(tokens: &[(Token, usize)], mut k: usize) -> bool {
    if k > 0 && tokens[k - 1].0 == Token::Ident("pub".into()) {
        k -= 1;
    }
    let want = [
        Token::Punct('#'),
        Token::Punct('['),
        Token::Ident("cfg".into()),
        Token::Punct('('),
        Token::Ident("test".into()),
        Token::Punct(')'),
        Token::Punct(']'),
    ];
    k >= want.len()
        && tokens[k - want.len()..k]
            .iter()
            .map(|t| &t.0)
            .eq(want.iter())
}

/// The files of one crate, found from `root` through `mod` declarations.
fn module_tree(root: &Path) -> Vec<ModuleFile> {
    let mut files = Vec::new();
    let mut stack = vec![(root.to_path_buf(), Vec::<String>::new(), true, false)];
    let mut seen = BTreeSet::new();
    while let Some((path, module, dir_owner, test)) = stack.pop() {
        if !seen.insert(path.clone()) {
            continue;
        }
        let Ok(src) = fs::read_to_string(&path) else {
            continue;
        };
        let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        // a `foo.rs` owns the directory `foo/` for its children; lib.rs, main.rs, mod.rs their own
        let child_dir = if dir_owner {
            dir.clone()
        } else {
            dir.join(path.file_stem().unwrap_or_default())
        };
        let tokens = tokenize(&src);
        let mut pending_path: Option<String> = None;
        for k in 0..tokens.len() {
            if tokens[k].0 == Token::Punct('#')
                && let Some(p) = path_attribute(&src, tokens[k].1)
            {
                pending_path = Some(p);
            }
            if tokens[k].0 == Token::Ident("mod".into())
                && let (Some((Token::Ident(name), _)), Some((Token::Punct(';'), _))) =
                    (tokens.get(k + 1), tokens.get(k + 2))
            {
                let mut child = module.clone();
                child.push(name.clone());
                let test = test || after_cfg_test(&tokens, k);
                if let Some(p) = pending_path.take() {
                    stack.push((dir.join(p), child, true, test));
                } else {
                    let flat = child_dir.join(format!("{name}.rs"));
                    if flat.exists() {
                        stack.push((flat, child, false, test));
                    } else {
                        stack.push((child_dir.join(name).join("mod.rs"), child, true, test));
                    }
                }
            } else if matches!(tokens[k].0, Token::Punct(';' | '{' | '}')) {
                pending_path = None;
            }
        }
        files.push(ModuleFile { path, module, test });
    }
    files
}

/// The `"…"` of a `#[path = "…"]` attribute on `line` of `src`, if there is one.
fn path_attribute(src: &str, line: usize) -> Option<String> {
    let text = src.lines().nth(line - 1)?.trim();
    let rest = text
        .strip_prefix("#[path")?
        .trim_start()
        .strip_prefix('=')?
        .trim();
    let rest = rest.strip_prefix('"')?;
    Some(rest[..rest.find('"')?].to_owned())
}

/// The references between peer files of one crate.
fn crate_edges(files: &[ModuleFile]) -> Vec<Edge> {
    let by_module: BTreeMap<&[String], &Path> = files
        .iter()
        .map(|f| (f.module.as_slice(), f.path.as_path()))
        .collect();
    let mut edges = BTreeSet::new();
    for file in files {
        let Ok(src) = fs::read_to_string(&file.path) else {
            continue;
        };
        let tokens = tokenize(&src);
        // inline modules (`mod tests { … }`): their names, the brace depth they close at and
        // whether they are test code
        let mut inline: Vec<(String, usize, bool)> = Vec::new();
        let mut depth = 0usize;
        let mut k = 0;
        while k < tokens.len() {
            match &tokens[k].0 {
                Token::Punct('{') => depth += 1,
                Token::Punct('}') => {
                    depth = depth.saturating_sub(1);
                    if inline.last().is_some_and(|(_, d, _)| *d == depth) {
                        inline.pop();
                    }
                }
                Token::Ident(m) if m == "mod" => {
                    if let (Some((Token::Ident(name), _)), Some((Token::Punct('{'), _))) =
                        (tokens.get(k + 1), tokens.get(k + 2))
                    {
                        inline.push((name.clone(), depth, after_cfg_test(&tokens, k)));
                    }
                }
                Token::Ident(head)
                    if matches!(head.as_str(), "crate" | "super" | "self")
                        && k > 0
                        && tokens[k - 1].0 != Token::PathSep
                        && tokens.get(k + 1).map(|t| &t.0) == Some(&Token::PathSep) =>
                {
                    let mut here = file.module.clone();
                    here.extend(inline.iter().map(|(n, _, _)| n.clone()));
                    let test = file.test || inline.iter().any(|(_, _, t)| *t);
                    let line = tokens[k].1;
                    let (paths, next) = parse_tree(&tokens, k, Vec::new());
                    for p in paths {
                        if let Some(target) = resolve(&p, &here, &by_module)
                            && target.path != file.path
                            && !is_prefix(&target.module, &file.module)
                            && !is_prefix(&file.module, &target.module)
                        {
                            edges.insert(Edge {
                                from: file.path.clone(),
                                to: target.path.to_path_buf(),
                                line,
                                test,
                            });
                        }
                    }
                    k = next.max(k + 1);
                    continue;
                }
                _ => {}
            }
            k += 1;
        }
    }
    edges.into_iter().collect()
}

struct Target<'a> {
    path: &'a Path,
    module: Vec<String>,
}

/// The file a path (`crate::a::b`, `super::super::c`, `self::d`) seen from module `here` names.
fn resolve<'a>(
    path: &[String],
    here: &[String],
    by_module: &BTreeMap<&[String], &'a Path>,
) -> Option<Target<'a>> {
    let mut base: Vec<String> = match path.first()?.as_str() {
        "crate" => Vec::new(),
        "self" | "super" => here.to_vec(),
        _ => return None,
    };
    let mut rest = &path[1..];
    if path[0] == "super" {
        base.pop()?;
        while rest.first().map(String::as_str) == Some("super") {
            base.pop()?;
            rest = &rest[1..];
        }
    }
    base.extend(rest.iter().cloned());
    (0..=base.len()).rev().find_map(|len| {
        by_module.get(&base[..len]).map(|p| Target {
            path: p,
            module: base[..len].to_vec(),
        })
    })
}

fn is_prefix(a: &[String], b: &[String]) -> bool {
    a.len() <= b.len() && a == &b[..a.len()]
}

/// The crate roots of the package in `dir` (a directory with a `Cargo.toml`).
fn crate_roots(dir: &Path) -> Vec<PathBuf> {
    let mut roots = Vec::new();
    for f in ["src/lib.rs", "src/main.rs"] {
        if dir.join(f).exists() {
            roots.push(dir.join(f));
        }
    }
    for sub in ["src/bin", "tests", "benches", "examples", "fuzz_targets"] {
        let Ok(entries) = fs::read_dir(dir.join(sub)) else {
            continue;
        };
        let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        entries.sort();
        for p in entries {
            if p.extension().is_some_and(|e| e == "rs") {
                roots.push(p);
            } else if p.join("main.rs").exists() {
                roots.push(p.join("main.rs"));
            }
        }
    }
    roots
}

/// Every package directory under `root` (skipping `target/`, hidden directories and virtualenvs).
fn packages(root: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        if dir.join("Cargo.toml").exists() {
            found.push(dir.clone());
        }
        let Ok(entries) = fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if e.path().is_dir()
                && !name.starts_with('.')
                && !matches!(name.as_str(), "target" | "node_modules" | "venv")
            {
                stack.push(e.path());
            }
        }
    }
    found.sort();
    found
}

/// The import loops of every crate under `root`, paths relative to `root`: with `tests`, the
/// references made by test code count too.
pub fn find(root: &Path, tests: bool) -> Vec<Loop> {
    let mut loops = Vec::new();
    for package in packages(root) {
        for crate_root in crate_roots(&package) {
            let files = module_tree(&crate_root);
            let mut edges = crate_edges(&files);
            edges.retain(|e| tests || !e.test);
            for component in strongly_connected(&edges) {
                let inside: BTreeSet<&PathBuf> = component.iter().collect();
                let relative = |p: &Path| p.strip_prefix(root).unwrap_or(p).to_path_buf();
                let edges = edges
                    .iter()
                    .filter(|e| inside.contains(&e.from) && inside.contains(&e.to))
                    .map(|e| Edge {
                        from: relative(&e.from),
                        to: relative(&e.to),
                        ..e.clone()
                    })
                    .collect();
                let files = component.iter().map(|p| relative(p)).collect();
                // a module file shared by several roots (`#[path]`) is reported once
                if !loops.iter().any(|l: &Loop| l.files == files) {
                    loops.push(Loop { files, edges });
                }
            }
        }
    }
    loops
}

/// Strongly connected components of two or more files (Tarjan 1972).
fn strongly_connected(edges: &[Edge]) -> Vec<Vec<PathBuf>> {
    let mut next: BTreeMap<&PathBuf, Vec<&PathBuf>> = BTreeMap::new();
    for e in edges {
        next.entry(&e.from).or_default().push(&e.to);
        next.entry(&e.to).or_default();
    }
    struct State<'a> {
        index: BTreeMap<&'a PathBuf, usize>,
        low: BTreeMap<&'a PathBuf, usize>,
        stack: Vec<&'a PathBuf>,
        on_stack: BTreeSet<&'a PathBuf>,
        out: Vec<Vec<PathBuf>>,
    }
    fn visit<'a>(
        v: &'a PathBuf,
        next: &BTreeMap<&'a PathBuf, Vec<&'a PathBuf>>,
        s: &mut State<'a>,
    ) {
        let i = s.index.len();
        s.index.insert(v, i);
        s.low.insert(v, i);
        s.stack.push(v);
        s.on_stack.insert(v);
        for &w in &next[v] {
            if !s.index.contains_key(w) {
                visit(w, next, s);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).expect("visited");
                *lv = (*lv).min(lw);
            } else if s.on_stack.contains(w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).expect("visited");
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(w);
                component.push(w.clone());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                s.out.push(component);
            }
        }
    }
    let mut s = State {
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in next.keys() {
        if !s.index.contains_key(v) {
            visit(v, &next, &mut s);
        }
    }
    s.out.sort();
    s.out
}

/// One loop as text: its files, then every reference between them (file:line).
fn describe(l: &Loop) -> String {
    let names: Vec<String> = l.files.iter().map(|p| p.display().to_string()).collect();
    let mut text = format!("import loop: {}", names.join(" <-> "));
    for e in &l.edges {
        let test = if e.test { " (test code)" } else { "" };
        text += &format!(
            "\n  {}:{} uses {}{test}",
            e.from.display(),
            e.line,
            e.to.display()
        );
    }
    text
}

/// `cargo xtask loops [--tests]`: print the import loops of the tree; `Err` (exit code 1) if
/// there is one. Without `--tests`, references made by `#[cfg(test)]` code (a unit test using
/// another module's method as its oracle) are listed as notes and do not fail the check.
pub fn run(root: &Path, args: &[String]) -> Result<(), String> {
    let tests = match args {
        [] => false,
        [a] if a == "--tests" => true,
        [a] if a == "-h" || a == "--help" => {
            println!(
                "cargo xtask loops [--tests]: the files of the tree that import each other in a loop (exit code 1 if any); --tests counts the references of test code too"
            );
            return Ok(());
        }
        _ => return Err(format!("usage: cargo xtask loops [--tests], got {args:?}")),
    };
    let loops = find(root, tests);
    for l in &loops {
        println!("{}", describe(l));
    }
    if !tests {
        for l in find(root, true) {
            if !loops
                .iter()
                .any(|c| c.files.iter().any(|f| l.files.contains(f)))
            {
                println!("note: only test code closes this loop\n{}", describe(&l));
            }
        }
    }
    if loops.is_empty() {
        println!("no import loops");
        Ok(())
    } else {
        Err(format!("{} import loop(s)", loops.len()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paths(src: &str) -> Vec<String> {
        let tokens = tokenize(src);
        let mut out = Vec::new();
        let mut k = 0;
        while k < tokens.len() {
            if matches!(&tokens[k].0, Token::Ident(h) if h == "crate" || h == "super") {
                let (p, next) = parse_tree(&tokens, k, Vec::new());
                out.extend(p.into_iter().map(|p| p.join("::")));
                k = next;
            } else {
                k += 1;
            }
        }
        out
    }

    #[test]
    fn use_trees_expand_groups_and_skip_comments_and_strings() {
        let src = r##"
            use super::{CliError, workspace::{box_json, draw_pose as d}, self};
            // use super::commented::Out;
            /* use crate::block::{Out}; /* nested */ */
            let s = "super::in_string::Out"; let r = r#"crate::raw::Out"#;
            let c = '"'; let l: &'static str = x; let e = '\'';
            crate::tension::run(a)
        "##;
        assert_eq!(
            paths(src),
            [
                "super::CliError",
                "super::workspace::box_json",
                "super::workspace::draw_pose",
                "super",
                "crate::tension::run"
            ]
        );
    }

    fn write(dir: &Path, files: &[(&str, &str)]) {
        for (name, text) in files {
            let p = dir.join(name);
            fs::create_dir_all(p.parent().unwrap()).unwrap();
            fs::write(p, text).unwrap();
        }
    }

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("xtask-loops-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn a_loop_between_siblings_is_found_and_the_module_tree_is_not() {
        let dir = scratch("siblings");
        write(
            &dir,
            &[
                ("Cargo.toml", "[package]\n"),
                ("src/lib.rs", "mod cli;\nmod lone;\npub fn helper() {}\n"),
                // parent <-> child references are the module tree: not loops
                (
                    "src/cli/mod.rs",
                    "pub mod a;\npub mod b;\npub fn load() {}\nfn run() { a::run(); b::run(); }\n",
                ),
                (
                    "src/cli/a.rs",
                    "use super::load;\nuse crate::helper;\npub fn run() { super::b::draw(); }\n#[cfg(test)]\nmod tests { use super::*; }\n",
                ),
                (
                    "src/cli/b.rs",
                    "use super::{a::run as r, load};\npub fn draw() {}\n",
                ),
                ("src/lone.rs", "use crate::cli::a::run;\n"),
            ],
        );
        let loops = find(&dir, false);
        assert_eq!(loops.len(), 1, "{loops:?}");
        assert_eq!(
            loops[0].files,
            [PathBuf::from("src/cli/a.rs"), PathBuf::from("src/cli/b.rs")]
        );
        assert_eq!(
            loops[0].edges,
            [
                Edge {
                    from: "src/cli/a.rs".into(),
                    to: "src/cli/b.rs".into(),
                    line: 3,
                    test: false
                },
                Edge {
                    from: "src/cli/b.rs".into(),
                    to: "src/cli/a.rs".into(),
                    line: 1,
                    test: false
                },
            ]
        );
        // break the loop: b no longer names a
        write(
            &dir,
            &[("src/cli/b.rs", "use super::load;\npub fn draw() {}\n")],
        );
        assert!(find(&dir, true).is_empty());
        // a loop closed only by a test module counts with `tests` only
        write(
            &dir,
            &[(
                "src/cli/b.rs",
                "use super::load;\npub fn draw() {}\n#[cfg(test)]\nmod tests {\n    use super::super::a;\n}\n",
            )],
        );
        assert!(find(&dir, false).is_empty());
        let loops = find(&dir, true);
        assert_eq!(loops.len(), 1, "{loops:?}");
        assert!(
            loops[0].edges.iter().any(|e| e.test && e.line == 5),
            "{loops:?}"
        );
        let _ = fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_three_file_loop_through_crate_paths_and_inline_modules() {
        let dir = scratch("three");
        write(
            &dir,
            &[
                ("Cargo.toml", "[package]\n"),
                ("src/main.rs", "mod x;\nmod y;\nmod z;\nfn main() {}\n"),
                ("src/x.rs", "fn f() -> crate::y::T { todo!() }\n"),
                (
                    "src/y.rs",
                    "pub struct T;\nmod inner { use super::super::z::U; }\n",
                ),
                ("src/z.rs", "pub struct U;\nfn g() { crate::x::f(); }\n"),
            ],
        );
        let loops = find(&dir, false);
        assert_eq!(loops.len(), 1, "{loops:?}");
        assert_eq!(loops[0].files.len(), 3);
        let _ = fs::remove_dir_all(&dir);
    }

    /// The tree itself: no file imports another in a loop (issue 25).
    #[test]
    fn the_tree_has_no_import_loop() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        let loops = find(root, false);
        let text: Vec<String> = loops.iter().map(describe).collect();
        assert!(loops.is_empty(), "{}", text.join("\n"));
    }
}
