//! The crate's shape, checked from its sources: `src/lib.rs` declares the
//! modules in layers (foundations, the stages in data-flow order, what runs
//! them, where frames go), and a module may use only itself and modules
//! declared before it. That rules out import cycles (a cycle needs a use of
//! a later module) and keeps the pipeline's order readable in `lib.rs`.
//! Modules reach each other by their own paths, not through the root's
//! re-exports, which are for users.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// The modules `lib.rs` declares, in order.
fn declared(lib: &str) -> Vec<String> {
    lib.lines()
        .map(str::trim)
        .filter_map(|l| {
            let l = l.strip_prefix("pub ").unwrap_or(l);
            let name = l.strip_prefix("mod ")?.strip_suffix(';')?;
            Some(name.to_string())
        })
        .collect()
}

/// A source file without its comments and its unit tests (tests may use
/// any module).
fn code(src: &str) -> String {
    let src = match src.find("#[cfg(test)]\nmod tests") {
        Some(i) => &src[..i],
        None => src,
    };
    src.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every `crate::name` in `code`, with `use crate::{a, b::c}` lists
/// expanded to their first segments.
fn crate_paths(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        let after = &rest[i + "crate::".len()..];
        if let Some(list) = after.strip_prefix('{') {
            let end = list.find('}').unwrap_or(list.len());
            for item in list[..end].split(',') {
                let item = item.trim();
                let first = item.split("::").next().unwrap_or("").trim();
                if !first.is_empty() {
                    out.push(first.to_string());
                }
            }
        } else {
            let name: String = after
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            out.push(name);
        }
        rest = after;
    }
    out
}

/// The rule's violations: `(module, what it uses, why)`.
fn violations(order: &[String], sources: &BTreeMap<String, String>) -> Vec<String> {
    let rank = |m: &str| order.iter().position(|o| o == m);
    let mut out = Vec::new();
    for (module, src) in sources {
        let mine = rank(module).expect("a declared module");
        for used in crate_paths(&code(src)) {
            match rank(&used) {
                Some(r) if r > mine => out.push(format!(
                    "{module} uses {used}, which lib.rs declares after it"
                )),
                Some(_) => {}
                None => out.push(format!(
                    "{module} uses crate::{used}, a root re-export: use the module's own path"
                )),
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

/// Each declared module's code (see [`code`]), `src/m.rs` and everything
/// under `src/m/`, concatenated.
fn sources(order: &[String]) -> BTreeMap<String, String> {
    fn walk(dir: &Path, out: &mut String) {
        let Ok(entries) = fs::read_dir(dir) else {
            return;
        };
        let mut paths: Vec<_> = entries.map(|e| e.unwrap().path()).collect();
        paths.sort();
        for p in paths {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push_str(&code(&fs::read_to_string(&p).unwrap()));
                out.push('\n');
            }
        }
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    order
        .iter()
        .map(|m| {
            let file = src.join(format!("{m}.rs"));
            assert!(
                file.exists() || src.join(m).join("mod.rs").exists(),
                "no source for module {m}"
            );
            let mut text = fs::read_to_string(file)
                .map(|t| code(&t))
                .unwrap_or_default();
            walk(&src.join(m), &mut text);
            (m.clone(), text)
        })
        .collect()
}

fn lib() -> String {
    fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap()
}

#[test]
fn modules_use_only_modules_declared_before_them() {
    let order = declared(&lib());
    let found = violations(&order, &sources(&order));
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn lib_declares_the_stages_in_data_flow_order() {
    let order = declared(&lib());
    let stages = [
        "scene",
        "shade",
        "clip",
        "raster",
        "framebuffer",
        "fill",
        "frame",
        "blit",
        "encode",
    ];
    let at: Vec<usize> = stages
        .iter()
        .map(|s| order.iter().position(|o| o == s).unwrap())
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{order:?}");
    // What runs the stages comes after the last of them.
    for runner in ["options", "plan", "render", "animate"] {
        let r = order.iter().position(|o| o == runner).unwrap();
        assert!(r > at[at.len() - 1], "{runner} in {order:?}");
    }
}

#[test]
fn a_cycle_or_a_root_re_export_is_caught() {
    let order: Vec<String> = ["scene", "plan", "render"].map(String::from).to_vec();
    let mut sources = BTreeMap::new();
    sources.insert("scene".to_string(), "use crate::Renderer;\n".to_string());
    sources.insert(
        "plan".to_string(),
        "use crate::{render::Renderer, scene};\n// crate::render in a comment\n".to_string(),
    );
    sources.insert(
        "render".to_string(),
        "use crate::plan::Plan;\n#[cfg(test)]\nmod tests { use crate::Nothing; }\n".to_string(),
    );
    assert_eq!(
        violations(&order, &sources),
        [
            "plan uses render, which lib.rs declares after it",
            "scene uses crate::Renderer, a root re-export: use the module's own path",
        ]
    );
}

/// The lines of `src` before its unit tests (`#[cfg(test)] mod tests`).
fn lines_outside_tests(src: &str) -> usize {
    let end = src.find("#[cfg(test)]\nmod tests").unwrap_or(src.len());
    src[..end].lines().count()
}

/// Every file under `dir` for which `keep` holds, sorted; not `target` or
/// hidden folders and files.
fn files_where(dir: &Path, keep: &dyn Fn(&Path) -> bool, out: &mut Vec<std::path::PathBuf>) {
    let mut paths: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    paths.sort();
    for p in paths {
        let name = p.file_name().unwrap().to_string_lossy();
        if name.starts_with('.') || name == "target" {
            continue;
        }
        if p.is_dir() {
            files_where(&p, keep, out);
        } else if keep(&p) {
            out.push(p);
        }
    }
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    files_where(dir, &|p| p.extension().is_some_and(|e| e == "rs"), out);
}

/// `f`'s path from the repository's root, with `/` between folders.
fn relative(root: &Path, f: &Path) -> String {
    f.strip_prefix(root)
        .unwrap()
        .to_string_lossy()
        .replace('\\', "/")
}

/// The most lines a source file of the library or the program has outside
/// its unit tests: a file longer than this holds more than one job.
const MAX_LINES: usize = 800;

#[test]
fn no_source_file_is_over_800_lines_outside_its_tests() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    rust_files(&root.join("cli/src"), &mut files);
    let mut over = Vec::new();
    for f in &files {
        let name = relative(root, f);
        let n = lines_outside_tests(&fs::read_to_string(f).unwrap());
        if n > MAX_LINES {
            over.push(format!("{name}: {n} lines"));
        }
    }
    assert!(over.is_empty(), "{}", over.join("\n"));
}

/// Comparisons by which a stage would choose a path from the options
/// itself, a choice that is the plan's ([`rastty::Plan::lean`]).
const PATH_CHOICES: &[&str] = &[
    "Pipeline::",
    "Traversal::Scan",
    "== Precision::",
    "!= Precision::",
    "== Traversal::",
    "!= Traversal::",
    "== Aa::",
    "!= Aa::",
];

/// The modules above the plan that run a frame, whose paths the plan
/// chooses.
const RUNNERS: &[&str] = &["render"];

/// Where `src` (a module's code, without comments and tests) chooses a
/// path the plan chooses.
fn path_choices(src: &str) -> Vec<&'static str> {
    PATH_CHOICES
        .iter()
        .copied()
        .filter(|c| src.contains(c))
        .collect()
}

#[test]
fn no_module_above_the_plan_decides_a_path() {
    let order = declared(&lib());
    let sources = sources(&order);
    let plan = order.iter().position(|m| m == "plan").unwrap();
    for m in RUNNERS {
        assert!(order.iter().position(|o| o == m).unwrap() > plan, "{m}");
        let found = path_choices(&sources[*m]);
        assert!(found.is_empty(), "{m} chooses a path itself: {found:?}");
    }
    // The check sees a choice the plan should make.
    assert_eq!(
        path_choices("let lean = !p.full && opts.traversal != Traversal::Scan;"),
        ["Traversal::Scan", "!= Traversal::"]
    );
}

/// The modules `lib.rs` declares public.
fn public(lib: &str) -> Vec<String> {
    lib.lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod ")?.strip_suffix(';'))
        .map(String::from)
        .collect()
}

/// The first segment of each `pub use` path in `code`.
fn re_exported(code: &str) -> Vec<&str> {
    code.match_indices("pub use ")
        .map(|(i, _)| {
            let path = &code[i + "pub use ".len()..];
            let end = path.find([':', ';', ' ']).unwrap_or(path.len());
            &path[..end]
        })
        .collect()
}

/// The items a user can name two ways: a root re-export from a public
/// module (`rastty::Scene` and `rastty::scene::Scene`), or a public
/// module re-exporting another module's items or its own public
/// submodule's (`rastty::scene::Axis` beside `rastty::transform::Axis`).
fn two_ways(lib: &str, sources: &BTreeMap<String, String>) -> Vec<String> {
    let public = public(lib);
    let mut out = Vec::new();
    for first in re_exported(&code(lib)) {
        if public.iter().any(|p| p == first) {
            out.push(format!("the root re-exports from {first}, a public module"));
        }
    }
    for module in &public {
        let code = &sources[module];
        let subs: Vec<&str> = code
            .lines()
            .filter_map(|l| l.trim().strip_prefix("pub mod ")?.strip_suffix(';'))
            .collect();
        for first in re_exported(code) {
            if first == "crate" || first == "super" {
                out.push(format!("{module} re-exports another module's item"));
            } else if subs.contains(&first) {
                out.push(format!(
                    "{module} re-exports from {first}, its public submodule"
                ));
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

#[test]
fn each_public_item_is_reachable_one_way() {
    let lib = lib();
    let found = two_ways(&lib, &sources(&declared(&lib)));
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn an_item_reachable_two_ways_is_caught() {
    let lib = "pub mod scene;\nmod render;\npub use render::Renderer;\npub use scene::Scene;\n";
    let mut sources = BTreeMap::new();
    sources.insert(
        "scene".to_string(),
        "pub mod obj;\npub use obj::load;\npub use crate::transform::Axis;\nuse crate::color::Rgb;\n"
            .to_string(),
    );
    sources.insert(
        "render".to_string(),
        "pub use crate::plan::Plan;\n".to_string(),
    );
    assert_eq!(
        two_ways(lib, &sources),
        [
            "scene re-exports another module's item",
            "scene re-exports from obj, its public submodule",
            "the root re-exports from scene, a public module",
        ]
    );
}

/// The table of docs/planner.md, as the effects' declaration says it
/// (`rastty::Effect`: name, runs when, skipped when).
fn effects_table() -> String {
    let mut t = String::from("| stage | runs when | skipped when |\n|---|---|---|\n");
    for &e in rastty::Effect::ALL {
        t += &format!(
            "| {} | {} | {} |\n",
            e.name(),
            e.runs_when(),
            e.skipped_when()
        );
    }
    t
}

#[test]
fn the_planners_table_is_its_effects_declaration() {
    let doc =
        fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/planner.md")).unwrap();
    let want = effects_table();
    assert!(
        doc.contains(&want),
        "docs/planner.md's table is not src/plan/effects.rs's declaration; it should read:\n{want}"
    );
}

#[test]
fn explain_reports_every_declared_effect_in_order() {
    use rastty::{RenderOptions, Renderer, scene::Scene};
    let scene = Scene::of_mesh(rastty::scene::Shape::Torus.mesh(rastty::color::Rgb::WHITE));
    let opts = RenderOptions::default();
    let mut r = Renderer::new();
    r.render(&scene, &opts);
    let report = r.explain(&scene, &opts, std::time::Duration::ZERO, 0);
    let named: Vec<&str> = report
        .lines()
        .filter_map(|l| {
            rastty::Effect::ALL
                .iter()
                .find(|e| l.starts_with(&format!("{:<14} ", e.name())))
                .map(|e| e.name())
        })
        .collect();
    let all: Vec<&str> = rastty::Effect::ALL.iter().map(|e| e.name()).collect();
    assert_eq!(named, all);
}

#[test]
fn the_build_is_cargos_alone_with_no_linker_script() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    files_where(root, &|_| true, &mut files);
    let mut found = Vec::new();
    for f in &files {
        let name = relative(root, f);
        let base = f.file_name().unwrap().to_string_lossy();
        if name.ends_with(".ld") || base == "build.rs" {
            found.push(name);
        } else if base == "Cargo.toml" || name.ends_with(".cargo/config.toml") {
            let text = fs::read_to_string(f).unwrap();
            if text.contains("link-arg") || text.contains("rustflags") {
                found.push(format!("{name}: sets linker arguments"));
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}

/// The most lines the program's `main.rs` has: it parses, runs the
/// command and maps errors to exit codes; each command is its own module.
const MAIN_LINES: usize = 60;

#[test]
fn the_programs_main_only_parses_dispatches_and_maps_errors() {
    let main =
        fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("cli/src/main.rs")).unwrap();
    let n = lines_outside_tests(&main);
    assert!(n <= MAIN_LINES, "cli/src/main.rs has {n} lines");
    let code = code(&main);
    for stage in ["Renderer", "Encoder", "render_into", "Frame"] {
        assert!(!code.contains(stage), "cli/src/main.rs names {stage}");
    }
}

/// The stages: what draws samples, knowing nothing of what they become.
const STAGES: &[&str] = &[
    "src/render",
    "src/raster",
    "src/fill",
    "src/fill.rs",
    "src/shade.rs",
    "src/framebuffer.rs",
    "src/plan",
    "src/clip.rs",
    "src/transform.rs",
];

#[test]
fn the_output_trait_is_the_only_path_from_the_stages_to_an_output() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    let mut wrong = Vec::new();
    for f in &files {
        let name = relative(root, f);
        let code = code(&fs::read_to_string(f).unwrap());
        // Every output is an implementation of the trait, beside it.
        if code.contains("Output for ") && name != "src/output.rs" {
            wrong.push(format!("{name}: implements Output away from src/output.rs"));
        }
        // The renderer's public face (src/render/mod.rs) hands callers a
        // frame, through `render_to` like any output.
        let stage = STAGES
            .iter()
            .any(|s| name == *s || name.starts_with(&format!("{s}/")));
        if !stage || name == "src/render/mod.rs" {
            continue;
        }
        // The stages name no output's units and no way of making them.
        for unit in [
            "blit::",
            "encode::",
            "crate::frame::",
            "Cell",
            "cells_mut",
            "GlyphMode",
        ] {
            if code.contains(unit) {
                wrong.push(format!("{name}: names {unit}"));
            }
        }
        // What fills an output is called from the renderer's one path,
        // `Renderer::render_to`, and its bands.
        let calls = code.matches("out.begin(").count() + code.matches("O::fill(").count();
        if calls > 0 && name != "src/render/mod.rs" && name != "src/render/bands.rs" {
            wrong.push(format!("{name}: fills an output itself"));
        }
    }
    let render = code(&fs::read_to_string(root.join("src/render/mod.rs")).unwrap());
    assert_eq!(
        render.matches("out.begin(").count(),
        1,
        "one path begins an output"
    );
    for public in [
        "pub fn render_into",
        "pub fn try_render_into",
        "fn render_checked",
    ] {
        let body = &render[render.find(public).unwrap()..];
        let body = &body[..body.find("\n    }").unwrap()];
        assert!(
            body.contains("self.render_to("),
            "{public} draws through render_to"
        );
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// Where `#[inline(always)]` stands: the stages docs/figures.md's
/// "Inlining" section measures it paying in (the rasterizer, fill, vertex,
/// shading and encoding stages, and the OBJ reader with its normals).
const FORCED_INLINING: &[&str] = &[
    "src/blit.rs",
    "src/color/mod.rs",
    "src/encode/cell.rs",
    "src/encode/sgr.rs",
    "src/fill.rs",
    "src/fill/",
    "src/fixed.rs",
    "src/framebuffer.rs",
    "src/raster/",
    "src/render/",
    "src/shade.rs",
    "src/transform.rs",
    "src/scene/normals.rs",
    "src/scene/obj/faces.rs",
    "src/scene/obj/fast.rs",
    "src/scene/topology.rs",
];

#[test]
fn inlining_is_forced_only_where_the_figures_show_it_pays() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    rust_files(&root.join("cli/src"), &mut files);
    let mut elsewhere = Vec::new();
    for f in &files {
        let name = relative(root, f);
        let forced = fs::read_to_string(f)
            .unwrap()
            .matches("#[inline(always)]")
            .count();
        let listed = FORCED_INLINING
            .iter()
            .any(|p| name == *p || (p.ends_with('/') && name.starts_with(p)));
        if forced > 0 && !listed {
            elsewhere.push(format!("{name}: {forced}"));
        }
    }
    assert!(elsewhere.is_empty(), "{}", elsewhere.join("\n"));
    let figures = fs::read_to_string(root.join("docs/figures.md")).unwrap();
    assert!(
        figures.contains("## Inlining"),
        "docs/figures.md measures the inlining"
    );
}

/// Every file of the repository a document names by its path, every
/// example it runs and every command it gives exists: a document that
/// names what has gone is wrong.
#[test]
fn the_documents_name_only_files_and_commands_that_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages = vec![root.join("README.md")];
    let mut docs: Vec<_> = fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    let mut stale = Vec::new();
    for page in &pages {
        let text = fs::read_to_string(page).unwrap();
        let name = relative(root, page);
        let bytes = text.as_bytes();
        for prefix in [
            "tests/",
            "cli/",
            "src/",
            "scripts/",
            "examples/",
            "measure/",
            "docs/",
        ] {
            for (i, _) in text.match_indices(prefix) {
                let starts_word = i == 0
                    || !(bytes[i - 1].is_ascii_alphanumeric() || b"_/.-".contains(&bytes[i - 1]));
                if !starts_word {
                    continue;
                }
                let path: String = text[i..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || "_/.-".contains(*c))
                    .collect();
                let path = path.trim_end_matches(['.', '/']);
                // Only whole paths of files with an extension, or folders.
                if !path.contains('.') && !path.ends_with(char::is_alphanumeric) {
                    continue;
                }
                if !root.join(path).exists() {
                    stale.push(format!("{name}: {path}"));
                }
            }
        }
        for (i, _) in text.match_indices("--example ") {
            let ex: String = text[i + "--example ".len()..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !root.join("examples").join(format!("{ex}.rs")).exists() {
                stale.push(format!("{name}: --example {ex}"));
            }
        }
        for gone in ["cargo bench", "criterion", "hot-functions"] {
            if text.contains(gone) {
                stale.push(format!("{name}: {gone}"));
            }
        }
    }
    assert!(stale.is_empty(), "{}", stale.join("\n"));
}

/// `text` holds `number` as a whole figure (not part of a longer one).
fn holds_figure(text: &str, number: &str) -> bool {
    let digit = |c: Option<char>| c.is_some_and(|c| c.is_ascii_digit());
    text.match_indices(number).any(|(i, _)| {
        let mut before = text[..i].chars().rev();
        let b = before.next();
        let rest = &text[i + number.len()..];
        let mut after = rest.chars();
        let a = after.next();
        let decimal_before = b == Some('.') && digit(before.next());
        let decimal_after = a == Some('.') && digit(after.next());
        !digit(b) && !decimal_before && !digit(a) && !decimal_after
    })
}

/// The README's one performance table quotes docs/figures.md, which
/// `scripts/figures.sh` writes: each figure is there, and each ratio is
/// the two figures beside it.
#[test]
fn the_readmes_performance_table_is_docs_figures() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = fs::read_to_string(root.join("README.md")).unwrap();
    let figures = fs::read_to_string(root.join("docs/figures.md")).unwrap();
    let section = &readme[readme.find("## Performance").unwrap()..];
    let section = &section[..section[3..].find("\n## ").unwrap() + 3];
    let rows: Vec<Vec<&str>> = section
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| what"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    assert!(rows.len() >= 4, "{section}");
    let value = |cell: &str| -> f64 {
        cell.trim_end_matches(['M', '×'])
            .replace(',', "")
            .parse()
            .unwrap_or_else(|_| panic!("not a figure: {cell:?}"))
    };
    for row in &rows {
        let (ours, peer, ratio) = (row[2], row[3], row[4]);
        for cell in [ours, peer].into_iter().filter(|c| !c.is_empty()) {
            let bare = cell.replace(',', "");
            assert!(
                holds_figure(&figures, &bare),
                "docs/figures.md does not have the README's {cell} ({})",
                row[1]
            );
        }
        if !ratio.is_empty() {
            let want = format!("{:.2}×", value(ours) / value(peer));
            assert_eq!(ratio, want, "{}", row[1]);
        }
    }
}
