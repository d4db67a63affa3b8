//! The faces keep up with the library: every public function and method of the Rust
//! library (`tests/public-api.txt`) has a row in `ffi/faces.md` naming the C functions of
//! `include/springwater.h` and the C# members of `csharp/Springwater/` that do its work, or
//! saying why a face has none. A function that lands in the library without a row fails
//! here; so does a row that names a C function or C# member that does not exist, a face
//! left out without a reason, and a `Surface` method whose C or C# twin of the same name
//! exists while its row leaves it out.
//!
//! The check is a function of four texts (the public API, the header, the C# sources, the
//! table), so the tests below also run it on small fixtures to show what it reports.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// What the check found: counts over the library's functions, and every problem.
#[derive(Debug, Default)]
struct Coverage {
    /// Public functions and methods of the library, each re-export once.
    capabilities: usize,
    /// Those whose row names a C function.
    in_c: usize,
    /// Those whose row names a C# member.
    in_csharp: usize,
    /// Those whose row leaves out C or C# (with a reason).
    differences: usize,
    /// Of the differences, those whose reason starts "Not yet": gaps to fill.
    not_yet: usize,
    problems: Vec<String>,
}

/// One row of the table: the Rust function, its C functions, its C# members, the reason.
#[derive(Debug)]
struct Row {
    line: usize,
    rust: String,
    c: Vec<String>,
    csharp: Vec<String>,
    why: String,
}

/// The public functions and methods (and trait methods) of `public-api.txt`, without the
/// crate's name: `Surface::advance`, `mesh::compute_normals`. An item re-exported under
/// another path (`floater::Floater::sphere` is `Floater::sphere`) is listed once, under its
/// shortest path: two lines are one item when they end in the same type and name and have
/// the same signature.
fn capabilities(api: &str) -> BTreeSet<String> {
    let mut shortest: BTreeMap<(String, String), String> = BTreeMap::new();
    for line in api.lines() {
        // `fn …`, `const fn …` (any qualifiers before `fn`), `trait-item …`.
        let item = match (line.strip_prefix("trait-item "), line.split_once("fn ")) {
            (Some(item), _) => item,
            (None, Some((qualifiers, item)))
                if qualifiers
                    .split_whitespace()
                    .all(|q| ["const", "async", "unsafe"].contains(&q)) =>
            {
                item
            }
            _ => continue,
        };
        let Some(rest) = item.strip_prefix("springwater::") else {
            continue;
        };
        let end = rest.find(['(', '<']).unwrap_or(rest.len());
        let (path, signature) = rest.split_at(end);
        let segments: Vec<&str> = path.split("::").collect();
        let name = segments[segments.len().saturating_sub(2)..].join("::");
        let entry = shortest
            .entry((name, signature.to_string()))
            .or_insert_with(|| path.to_string());
        if path.len() < entry.len() {
            *entry = path.to_string();
        }
    }
    shortest.into_values().collect()
}

/// The `sw_*` functions the header declares (not those its comments mention).
fn header_functions(header: &str) -> BTreeSet<String> {
    let mut functions = BTreeSet::new();
    for line in header.lines().filter(|l| !l.trim_start().starts_with("//")) {
        for (at, _) in line.match_indices("sw_") {
            let starts_word = line[..at]
                .chars()
                .next_back()
                .is_none_or(|c| !c.is_alphanumeric() && c != '_');
            let name: String = line[at..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if starts_word && line[at + name.len()..].trim_start().starts_with('(') {
                functions.insert(name);
            }
        }
    }
    functions
}

/// The public members of the C# sources' types, as `Type.Member` (`new Type` for a
/// constructor): every `public` declaration inside a class or struct, by brace depth.
fn csharp_members(sources: &[String]) -> BTreeSet<String> {
    let mut members = BTreeSet::new();
    for source in sources {
        // The enclosing types, with the brace depth each was declared at.
        let mut types: Vec<(String, usize)> = Vec::new();
        let mut depth = 0usize;
        for line in source.lines() {
            let code = line.split("//").next().unwrap_or_default().trim();
            // A declaration's keyword comes before any call, value or string.
            let head = code.split(['(', '=', '"']).next().unwrap_or_default();
            let words: Vec<&str> = head.split_whitespace().collect();
            let declared = words
                .windows(2)
                .find(|w| ["class", "struct", "interface", "enum"].contains(&w[0]))
                .map(|w| identifier(w[1]));
            match (declared, types.last()) {
                (Some(name), _) => types.push((name, depth)),
                (None, Some((owner, _))) if code.starts_with("public ") => {
                    let head = code.split(['(', '=', '{', ';']).next().unwrap_or_default();
                    let name = head.split_whitespace().last().map(identifier);
                    match name {
                        Some(name) if name == *owner && code.contains('(') => {
                            members.insert(format!("new {owner}"));
                        }
                        Some(name) if !name.is_empty() => {
                            members.insert(format!("{owner}.{name}"));
                        }
                        _ => {}
                    }
                }
                _ => {}
            }
            for c in code.chars() {
                match c {
                    '{' => depth += 1,
                    '}' => {
                        depth = depth.saturating_sub(1);
                        if types.last().is_some_and(|(_, at)| depth <= *at) {
                            types.pop();
                        }
                    }
                    _ => {}
                }
            }
        }
    }
    members
}

/// The identifier at the start of `word` (`Name` of `Name<T>`, `Name:`).
fn identifier(word: &str) -> String {
    word.chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// The table's rows: every line `| `Rust` | C | C# | why |`; a cell of C or C# names is
/// backticked names separated by commas, or `—`.
fn rows(table: &str) -> Vec<Row> {
    let names = |cell: &str| -> Vec<String> {
        cell.split(',')
            .map(|n| n.trim().trim_matches('`').to_string())
            .filter(|n| !n.is_empty() && n != "—")
            .collect()
    };
    table
        .lines()
        .enumerate()
        .filter(|(_, l)| l.starts_with("| `"))
        .map(|(i, l)| {
            let cells: Vec<&str> = l.trim().trim_matches('|').split(" | ").collect();
            let cell = |k: usize| cells.get(k).map_or("", |c| c.trim());
            Row {
                line: i + 1,
                rust: cell(0).trim_matches('`').to_string(),
                c: names(cell(1)),
                csharp: names(cell(2)),
                why: cell(3).to_string(),
            }
        })
        .collect()
}

/// `set_step_cap` → `SetStepCap`.
fn pascal(name: &str) -> String {
    name.split('_')
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_uppercase().chain(c).collect::<String>())
                .unwrap_or_default()
        })
        .collect()
}

/// Checks the table against the public API, the header and the C# sources.
fn check(api: &str, header: &str, csharp: &[String], table: &str) -> Coverage {
    let capabilities = capabilities(api);
    let functions = header_functions(header);
    let members = csharp_members(csharp);
    let mut coverage = Coverage {
        capabilities: capabilities.len(),
        ..Coverage::default()
    };
    let problems = &mut coverage.problems;
    let mut seen = BTreeSet::new();
    for row in rows(table) {
        let at = format!("faces.md:{} `{}`", row.line, row.rust);
        if !seen.insert(row.rust.clone()) {
            problems.push(format!("{at}: a second row for it"));
        }
        if !capabilities.contains(&row.rust) {
            problems.push(format!(
                "{at}: no public function of the library has this name (gone, or renamed?)"
            ));
            continue;
        }
        for c in row.c.iter().filter(|c| !functions.contains(*c)) {
            problems.push(format!("{at}: the header declares no `{c}`"));
        }
        for m in row.csharp.iter().filter(|m| !members.contains(*m)) {
            problems.push(format!("{at}: the C# sources declare no public `{m}`"));
        }
        if (row.c.is_empty() || row.csharp.is_empty()) && row.why.is_empty() {
            problems.push(format!(
                "{at}: leaves out C or C# without saying why (fill in the last column)"
            ));
        }
        if let Some(method) = row.rust.strip_prefix("Surface::") {
            let c = format!("sw_surface_{method}");
            if functions.contains(&c) && !row.c.contains(&c) {
                problems.push(format!("{at}: the header has `{c}`; name it in the row"));
            }
            let m = format!("WaterSurface.{}", pascal(method));
            if members.contains(&m) && !row.csharp.contains(&m) {
                problems.push(format!("{at}: the C# has `{m}`; name it in the row"));
            }
        }
        coverage.in_c += !row.c.is_empty() as usize;
        coverage.in_csharp += !row.csharp.is_empty() as usize;
        if row.c.is_empty() || row.csharp.is_empty() {
            coverage.differences += 1;
            coverage.not_yet += row.why.starts_with("Not yet") as usize;
        }
    }
    for missing in capabilities.difference(&seen) {
        problems.push(format!(
            "`{missing}` is public but has no row in ffi/faces.md: add its C function and C# \
             member (and the row), or say in the row why a face has none"
        ));
    }
    coverage
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn every_public_function_has_its_c_and_csharp_face_or_a_reason() {
    let ffi = Path::new(env!("CARGO_MANIFEST_DIR"));
    let api = read(&ffi.join("../tests/public-api.txt"));
    let header = read(&ffi.join("include/springwater.h"));
    let mut csharp: Vec<_> = std::fs::read_dir(ffi.join("csharp/Springwater"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "cs"))
        .collect();
    csharp.sort();
    let csharp: Vec<String> = csharp.iter().map(|p| read(p)).collect();
    let table = read(&ffi.join("faces.md"));

    // Plausible sizes: a parse that found nothing cannot pass.
    assert!(
        capabilities(&api).len() >= 200,
        "too few public functions parsed"
    );
    assert!(
        header_functions(&header).len() >= 70,
        "too few C functions parsed"
    );
    let members = csharp_members(&csharp);
    assert!(members.len() >= 150, "too few C# members parsed");
    assert!(members.contains("new WaterSurface") && members.contains("WaterSurface.Advance"));
    assert!(rows(&table).len() >= 200, "too few rows parsed in faces.md");

    let coverage = check(&api, &header, &csharp, &table);
    println!(
        "{} public functions: {} in C, {} in C#, {} deliberate differences or gaps ({} not yet)",
        coverage.capabilities,
        coverage.in_c,
        coverage.in_csharp,
        coverage.differences,
        coverage.not_yet
    );
    assert!(
        coverage.problems.is_empty(),
        "ffi/faces.md is out of step with the library, the header or the C#:\n{}",
        coverage.problems.join("\n")
    );
    assert!(coverage.in_c >= 90 && coverage.in_csharp >= 90);
}

// ---- The check on fixtures ----

const API: &str = "\
fn springwater::Surface::new(params: Params) -> Result<Self>
fn springwater::Surface::set_mass(&mut self, node: usize, mass: f32) -> Result<()>
fn springwater::Floater::sphere(radius: f32) -> Self
fn springwater::floater::Floater::sphere(radius: f32) -> Self
const fn springwater::Grid::index(&self, col: usize, row: usize) -> usize
trait-item springwater::JobSystem::workers(&self) -> usize
#[deprecated] springwater::Surface::len
field springwater::Params::mass: f32
";

const HEADER: &str = "\
// sw_surface_mentioned(void) in a comment is no function
SwStatus sw_surface_create(const SwParams *params,
                           SwSurface **out);
SwStatus sw_surface_set_mass(SwSurface *surface, size_t node, float mass);
";

const CSHARP: &str = "\
namespace Springwater
{
    public sealed partial class WaterSurface : IDisposable
    {
        public WaterSurface(int cols, int rows) { }
        public void SetMass(int node, float mass) { }
        struct Hidden
        {
            public int Inside;
        }
        public int NodeCount
        {
            get { return 0; }
        }
    }
}
";

const TABLE: &str = "\
| Rust | C | C# | why |
|---|---|---|---|
| `Surface::new` | `sw_surface_create` | `new WaterSurface` | |
| `Floater::sphere` | — | — | Rust-only: a fixture |
| `Grid::index` | — | — | Rust-only: grid math |
| `JobSystem::workers` | — | — | Not yet: a fixture |
";

fn fixture(table: &str) -> Coverage {
    check(API, HEADER, &[CSHARP.to_string()], table)
}

#[test]
fn the_parsers_find_functions_declarations_and_members() {
    let found = capabilities(API);
    let want = [
        "Floater::sphere",
        "Grid::index",
        "JobSystem::workers",
        "Surface::new",
        "Surface::set_mass",
    ];
    assert_eq!(found.iter().map(String::as_str).collect::<Vec<_>>(), want);
    let functions = header_functions(HEADER);
    assert_eq!(
        functions.into_iter().collect::<Vec<_>>(),
        ["sw_surface_create", "sw_surface_set_mass"]
    );
    let members = csharp_members(&[CSHARP.to_string()]);
    let want = [
        "Hidden.Inside",
        "WaterSurface.NodeCount",
        "WaterSurface.SetMass",
        "new WaterSurface",
    ];
    assert_eq!(members.iter().map(String::as_str).collect::<Vec<_>>(), want);
}

#[test]
fn a_new_public_method_without_a_row_is_reported() {
    let coverage = fixture(TABLE);
    assert_eq!(coverage.problems.len(), 1, "{:?}", coverage.problems);
    assert!(coverage.problems[0].starts_with("`Surface::set_mass` is public but has no row"));
    assert_eq!(
        (coverage.capabilities, coverage.in_c, coverage.in_csharp),
        (5, 1, 1)
    );
    assert_eq!((coverage.differences, coverage.not_yet), (3, 1));

    let full = format!(
        "{TABLE}| `Surface::set_mass` | `sw_surface_set_mass` | `WaterSurface.SetMass` | |\n"
    );
    assert!(fixture(&full).problems.is_empty());
}

#[test]
fn rows_that_name_nothing_or_leave_a_face_out_silently_are_reported() {
    let cases = [
        (
            "| `Surface::set_mass` | `sw_surface_set_mass` | `WaterSurface.SetMasses` | |\n",
            "the C# sources declare no public `WaterSurface.SetMasses`",
        ),
        (
            "| `Surface::set_mass` | `sw_surface_gone` | `WaterSurface.SetMass` | |\n",
            "the header declares no `sw_surface_gone`",
        ),
        (
            "| `Surface::set_mass` | — | `WaterSurface.SetMass` | |\n",
            "leaves out C or C# without saying why",
        ),
        (
            "| `Surface::set_mass` | — | `WaterSurface.SetMass` | Not yet |\n",
            "the header has `sw_surface_set_mass`; name it in the row",
        ),
        (
            "| `Surface::set_mass` | `sw_surface_set_mass` | — | Not yet |\n",
            "the C# has `WaterSurface.SetMass`; name it in the row",
        ),
        (
            "| `Surface::set_mass` | `sw_surface_set_mass` | `WaterSurface.SetMass` | |\n\
             | `Surface::removed` | — | — | Rust-only |\n",
            "no public function of the library has this name",
        ),
        (
            "| `Surface::set_mass` | `sw_surface_set_mass` | `WaterSurface.SetMass` | |\n\
             | `Grid::index` | — | — | Rust-only |\n",
            "a second row for it",
        ),
    ];
    for (rows, problem) in cases {
        let coverage = fixture(&format!("{TABLE}{rows}"));
        assert!(
            coverage.problems.iter().any(|p| p.contains(problem)),
            "{rows}: {:?}",
            coverage.problems
        );
    }
}
