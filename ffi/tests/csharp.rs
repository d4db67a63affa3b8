//! The C# package in `ffi/csharp/`, compiled with Mono's `mcs -unsafe` and run with `mono`
//! on the release `libspringwater_ffi`:
//!
//! * `Tests~/Runner.cs`, the package's tests: a frame loop whose positions must equal the
//!   command line's CSV bit for bit, no allocation in the frame loop, every refusal with the
//!   library's message, `Dispose`, the finalizer, floating bodies and the moving window (their
//!   values recomputed here through the Rust API), snapshots and state hashes, two threads;
//!   `Tests~/RigidBodies.cs`: a box heeled 15° rights itself as a built-in body (its
//!   orientation the Rust API's bits), in an engine's own integrator driven by
//!   `BodyForces`, and as a `Hull`; `Tests~/Lattice.cs`: pins, masses, viscosities, a
//!   spring and a torque push, read back (the state's hash the Rust API's);
//!   `Tests~/Frames.cs`, `Tests~/Shapes.cs` and `Tests~/Disturbances.cs`: variable frames,
//!   every node's force and velocity, the LOD mesh from chosen levels, the hulls the
//!   library makes, a point's velocity on a body, rain and wakes (their values recomputed
//!   through the Rust API in `csharp_values/`);
//! * the declarations against `include/springwater.h`: every function, constant, struct,
//!   field, size and offset of the header (the C compiler's `sizeof` and `offsetof`) must be
//!   in `Native` and the structs with the same types (`Tests~/Layout.cs` prints them);
//! * the Unity package: its layout, and its sources and sample compiled against stand-ins
//!   for `UnityEngine` (`Tests~/UnityStubs.cs`) with Unity's scripting defines.
//!
//! Needs `mcs` and `mono` (Debian's `mono-mcs` and `mono-runtime`) and `cc`: without them
//! the tests say so and pass, unless `SPRINGWATER_REQUIRE_TOOLS` is set, where they fail.

mod common;
mod csharp_values;

use common::{assert_ok, build_release, floater_floats, fnv, righted_box, tool_missing};
use springwater::{Boundary, Family, Floater, FloaterId, Params, Spring, SpringId, Surface};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn crate_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn package_dir() -> PathBuf {
    crate_dir().join("csharp")
}

/// Whether Mono's compiler and runtime are here; a test that cannot run says why, and
/// fails where CI installed the tools (`SPRINGWATER_REQUIRE_TOOLS`).
fn have_mono() -> bool {
    let runs = |tool: &str| {
        Command::new(tool)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    };
    if runs("mcs") && runs("mono") {
        return true;
    }
    tool_missing("Mono is not installed (apt-get install mono-mcs mono-runtime)");
    false
}

/// A directory for one test's compiled programs and output, beside the C clients'.
fn scratch(test: &str) -> PathBuf {
    let root = crate_dir().parent().unwrap();
    let dir = root.join("target").join("ffi-c").join("csharp").join(test);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The release C ABI and command line, built into `target/ffi-c/`.
fn release_dir() -> &'static Path {
    static BUILT: OnceLock<PathBuf> = OnceLock::new();
    BUILT.get_or_init(|| build_release(&["springwater-ffi", "springwater-cli"], None))
}

/// The package's runtime sources: `Springwater/*.cs`, as a client compiles them.
fn runtime_sources() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(package_dir().join("Springwater"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "cs"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 5,
        "C# sources missing in ffi/csharp/Springwater: {files:?}"
    );
    files
}

/// `Tests~/name`.
fn test_source(name: &str) -> PathBuf {
    package_dir().join("Tests~").join(name)
}

/// Compiles the runtime sources and `files` with `flags` into `out`; warnings are errors.
fn mcs(out: &Path, flags: &[&str], files: &[PathBuf]) {
    mcs_only(out, flags, &[runtime_sources(), files.to_vec()].concat());
}

/// Compiles `files` alone with `flags` into `out`; warnings are errors.
fn mcs_only(out: &Path, flags: &[&str], files: &[PathBuf]) {
    let out = Command::new("mcs")
        .args(["-unsafe", "-warn:4", "-warnaserror+", "-nologo"])
        .arg(format!("-out:{}", out.display()))
        .args(flags)
        .args(files)
        .output()
        .expect("mcs runs");
    assert_ok(&out, "compiling C#");
}

/// Runs a compiled program under Mono with the release library on its search path.
fn mono(exe: &Path, args: &[&Path]) -> Output {
    Command::new("mono")
        .arg("--debug")
        .arg(exe)
        .args(args)
        .env("LD_LIBRARY_PATH", release_dir())
        .output()
        .expect("mono runs")
}

fn positions_fnv(s: &Surface) -> String {
    let [x, y, z] = s.positions();
    format!(
        "{:016x}",
        fnv((0..s.node_count()).flat_map(|i| [x[i], y[i], z[i]]))
    )
}

const FRAME: f32 = 1.0 / 60.0;

/// `Floaters()` of Runner.cs through the Rust API.
fn floaters() -> Vec<(&'static str, String)> {
    let params = Params::with_size(40, 32).with_boundary(Boundary::Absorbing { width: 5 });
    let mut s = Surface::new(params).unwrap();
    let mut buoyancy = s.buoyancy();
    buoyancy.density = 1.2;
    s.set_buoyancy(buoyancy).unwrap();
    let mut ball = Floater::sphere(1.5, 5.0, [14.0, 0.5, 12.0]);
    ball.velocity = glam::Vec3::new(0.6, 0.0, 0.3);
    let a = s.add_floater(ball).unwrap();
    let boxy = s
        .add_floater(Floater::cuboid([2.0, 0.75, 1.0], 8.0, [26.0, 0.0, 18.0]))
        .unwrap();
    assert_eq!((a, boxy), (FloaterId::from_raw(0), FloaterId::from_raw(1)));
    s.drop_at(20.0, 16.0, 0.6, 2.5).unwrap();
    for frame in 0..50 {
        if frame == 20 {
            s.push_floater(a, [50.0, 0.0, -20.0]).unwrap();
        }
        s.advance(FRAME).unwrap();
    }
    let mut moved = s.floater(boxy).unwrap().clone();
    moved.position.x = 24.0;
    moved.position.z = 18.0;
    moved.drag = 12.0;
    s.set_floater(boxy, moved).unwrap();
    s.step_n(30).unwrap();
    let floats = [a, boxy]
        .into_iter()
        .flat_map(|id| floater_floats(s.floater(id).unwrap()));
    vec![
        ("floaters", format!("{:016x}", fnv(floats))),
        ("floaters_water", positions_fnv(&s)),
        ("floaters_hash", format!("{:016x}", s.state_hash())),
    ]
}

/// `Window()` of Runner.cs through the Rust API.
fn window() -> Vec<(&'static str, String)> {
    let params = Params::with_size(40, 32).with_boundary(Boundary::Free);
    let mut s = Surface::new(params).unwrap();
    s.drop_at(18.0, 14.0, 0.8, 3.0).unwrap();
    for _ in 0..20 {
        s.advance(FRAME).unwrap();
    }
    s.shift(5, -3).unwrap();
    let [ox, oz] = s.origin();
    assert_eq!(s.follow(ox + 20.0, oz + 16.0).unwrap(), [0, 0]);
    let [dc, dr] = s.follow(ox + 33.0, oz + 5.0).unwrap();
    for _ in 0..10 {
        s.advance(FRAME).unwrap();
    }
    s.rebase(2, 1).unwrap();
    let [ox, oz] = s.origin();
    let height = s.height_at(ox + 15.5, oz + 12.25).unwrap();
    vec![
        ("follow", format!("{dc} {dr}")),
        (
            "origin",
            format!("{:08x} {:08x}", ox.to_bits(), oz.to_bits()),
        ),
        ("window_height", format!("{:08x}", height.to_bits())),
        ("window", positions_fnv(&s)),
        ("window_hash", format!("{:016x}", s.state_hash())),
    ]
}

/// `Lattice()` of Lattice.cs through the Rust API.
fn lattice() -> Vec<(&'static str, String)> {
    let mut s = Surface::new(Params::with_size(20, 16)).unwrap();
    let masses: Vec<f32> = (0..320).map(|i| 4.0 + 0.25 * (i % 8) as f32).collect();
    s.set_masses(&masses).unwrap();
    s.set_mass(21, 5.0).unwrap();
    s.set_viscosity(5 * 20 + 5, 0.2).unwrap();
    s.set_pinned(8 * 20 + 10, true).unwrap();
    let spring = Spring {
        rest: 0.9,
        stiffness: 6.0,
    };
    let id = SpringId {
        family: Family::SE,
        origin: 6 * 20 + 6,
    };
    s.set_spring(id, spring).unwrap();
    let body = s
        .add_floater(Floater::cuboid([1.0, 0.5, 1.0], 2.0, [10.0, 0.0, 8.0]))
        .unwrap();
    s.push_floater_torque(body, [0.0, 30.0, 0.0]).unwrap();
    s.drop_at(10.0, 8.0, 0.5, 2.0).unwrap();
    s.advance(0.5).unwrap();
    vec![("lattice_hash", format!("{:016x}", s.state_hash()))]
}

/// The tests Runner.cs must report as passed.
const RUNNER_TESTS: &[&str] = &[
    "frame_loop_writes_what_the_command_line_computes",
    "the_frame_loop_allocates_nothing",
    "every_refusal_throws_the_library_message_and_changes_nothing",
    "dispose_twice_is_harmless_and_use_after_dispose_is_refused",
    "the_finalizer_destroys_forgotten_surfaces",
    "floating_bodies",
    "the_moving_window",
    "snapshots_round_trip_and_state_hashes_follow_the_state",
    "two_threads_each_owning_a_surface_get_the_same_bits",
    "queries_agree_with_the_buffers",
    "a_heeled_box_rights_itself",
    "the_lattice_node_by_node",
    "frames_forces_velocities_and_the_lod_mesh",
    "the_hulls_the_library_makes_and_points_on_bodies",
    "rain_and_wakes",
];

#[test]
fn the_csharp_tests_pass_under_mono_with_the_command_lines_bits() {
    if !have_mono() {
        return;
    }
    let dir = scratch("runner");
    let exe = dir.join("runner.exe");
    mcs(
        &exe,
        &[],
        &[
            test_source("Runner.cs"),
            test_source("RigidBodies.cs"),
            test_source("Lattice.cs"),
            test_source("Frames.cs"),
            test_source("Shapes.cs"),
            test_source("Disturbances.cs"),
        ],
    );
    let out = mono(&exe, &[&dir]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_ok(&out, "the C# tests");
    for name in RUNNER_TESTS {
        assert!(
            stdout.lines().any(|l| l == format!("ok {name}")),
            "the C# test {name} did not pass:\n{stdout}"
        );
    }
    let values: HashMap<&str, &str> = stdout
        .lines()
        .filter_map(|l| l.strip_prefix("value "))
        .filter_map(|l| l.split_once(' '))
        .collect();
    for (key, want) in floaters()
        .into_iter()
        .chain(window())
        .chain(righted_box())
        .chain(lattice())
        .chain(csharp_values::frames())
        .chain(csharp_values::shapes())
        .chain(csharp_values::disturbances())
    {
        assert_eq!(
            values.get(key).copied(),
            Some(want.as_str()),
            "the C# run's `{key}` differs from the Rust API's"
        );
    }

    // The frame loop's positions against `springwater simulate`'s CSV, node by node.
    let csv = dir.join("frame_loop.csv");
    let cli = Command::new(release_dir().join("springwater"))
        .args(["simulate", "--size", "48x40", "--steps", "90"])
        .args(["--drop", "20,15,1,3", "--csv"])
        .arg(&csv)
        .output()
        .expect("the command line runs");
    assert_ok(&cli, "springwater simulate");
    let csv = std::fs::read_to_string(&csv).unwrap();
    let ours = std::fs::read_to_string(dir.join("frame_loop.txt")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("col,row,x,y,z"));
    let mut nodes = 0;
    for (line, bits) in lines.zip(ours.lines()) {
        let fields: Vec<&str> = line.split(',').collect();
        let want: Vec<String> = fields[2..]
            .iter()
            .map(|v| format!("{:08x}", v.parse::<f32>().unwrap().to_bits()))
            .collect();
        assert_eq!(bits, want.join(" "), "node {},{}", fields[0], fields[1]);
        nodes += 1;
    }
    assert_eq!((nodes, ours.lines().count()), (48 * 40, 48 * 40));
}

// ---- The declarations against the header ----

/// What `springwater.h` declares: functions (return type, parameter types), structs (fields
/// with their C types), `SW_*` constants, and the typedefs the types go through.
#[derive(Default)]
struct Header {
    functions: Vec<(String, String, Vec<String>)>,
    structs: Vec<(String, Vec<(String, String)>)>,
    constants: Vec<String>,
    aliases: HashMap<String, String>,
}

/// Reads the header cbindgen writes: one declaration per `;`, structs as
/// `typedef struct Name { fields } Name;`, `//` comments, one `#define` per line.
fn parse_header(text: &str) -> Header {
    let mut header = Header::default();
    let mut code = String::new();
    for line in text.lines() {
        let line = line.split("//").next().unwrap();
        let line = match (line.find("/*"), line.find("*/")) {
            (Some(a), Some(b)) => format!("{}{}", &line[..a], &line[b + 2..]),
            _ => line.to_string(),
        };
        let trimmed = line.trim();
        if let Some(define) = trimmed.strip_prefix("#define SW_") {
            let name = define.split_whitespace().next().unwrap();
            header.constants.push(format!("SW_{name}"));
        } else if !(trimmed.starts_with('#') || trimmed == "extern \"C\" {" || trimmed == "}") {
            code.push_str(trimmed);
            code.push(' ');
        }
    }
    let mut open: Option<(String, Vec<(String, String)>)> = None;
    for statement in code.split(';').map(str::trim).filter(|s| !s.is_empty()) {
        let mut statement = statement;
        if let Some(rest) = statement.strip_prefix("typedef struct ") {
            if let Some((name, first)) = rest.split_once('{') {
                open = Some((name.trim().to_string(), Vec::new()));
                statement = first.trim();
            } else {
                continue; // the opaque SwSurface
            }
        }
        if let Some((name, mut fields)) = open.take() {
            if statement.starts_with('}') {
                header.structs.push((name, fields));
            } else {
                fields.push(split_declaration(statement));
                open = Some((name, fields));
            }
            continue;
        }
        if let Some(typedef) = statement.strip_prefix("typedef ") {
            if let Some(start) = typedef.find("(*") {
                let name = &typedef[start + 2..typedef[start..].find(')').unwrap() + start];
                header.aliases.insert(name.to_string(), "fn".to_string());
            } else {
                let (name, c_type) = split_declaration(typedef);
                header.aliases.insert(name, c_type);
            }
        } else if let Some(open_paren) = statement.find('(') {
            let (name, ret) = split_declaration(&statement[..open_paren]);
            let params = statement[open_paren + 1..statement.rfind(')').unwrap()].trim();
            let params = match params {
                "void" => Vec::new(),
                _ => params.split(',').map(|p| split_declaration(p).1).collect(),
            };
            header.functions.push((name, ret, params));
        }
    }
    assert!(open.is_none(), "an unterminated struct in the header");
    header
}

/// `const float *xz` → (`xz`, `const float *`); `float normal[3]` → (`normal`, `float[3]`).
fn split_declaration(declaration: &str) -> (String, String) {
    let declaration = declaration.trim();
    let (declaration, array) = match declaration.split_once('[') {
        Some((d, n)) => (d, format!("[{}", n)),
        None => (declaration, String::new()),
    };
    let at = declaration
        .rfind(|c: char| !(c.is_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1);
    let c_type = format!("{}{array}", declaration[..at].trim());
    (declaration[at..].to_string(), c_type)
}

/// The C# spelling (as Layout.cs prints it) that `Native` must use for a C type.
fn csharp_type(c_type: &str, aliases: &HashMap<String, String>, returned: bool) -> String {
    let c_type = c_type.replace("const ", "").replace("struct ", "");
    if let Some((element, length)) = c_type.split_once('[') {
        return format!("{}[{length}", csharp_type(element, aliases, false));
    }
    let stars = c_type.matches('*').count();
    let base = c_type.replace('*', "");
    let base = base.trim();
    let pointers = |n: usize| "*".repeat(n);
    match aliases.get(base).map(String::as_str) {
        Some("fn") => return format!("IntPtr{}", pointers(stars)),
        Some(target) if !target.contains('*') => {
            return csharp_type(&format!("{target}{}", pointers(stars)), aliases, returned)
        }
        _ => {}
    }
    // A `void *` and a returned string are addresses; a surface, a hull or a disturbance
    // is a handle.
    if stars == 1 && (base == "void" || (base == "char" && returned)) {
        return "IntPtr".into();
    }
    let primitive = match base {
        "SwSurface" | "SwHull" | "SwDisturbance" => {
            return format!("IntPtr{}", pointers(stars - 1))
        }
        "char" | "uint8_t" => "byte",
        "uint32_t" => "uint",
        "int32_t" => "int",
        "uint64_t" => "ulong",
        "int64_t" => "long",
        "size_t" => "UIntPtr",
        other => other, // float, double, void, the Sw structs
    };
    format!("{primitive}{}", pointers(stars))
}

/// A C program that prints, from the C compiler, what Layout.cs prints from the CLR:
/// `struct NAME SIZE`, `field NAME.FIELD OFFSET SIZE`, `const NAME VALUE`.
fn c_layout_program(header: &Header) -> String {
    let mut c = String::from(
        "#include <stddef.h>\n#include <stdio.h>\n#include \"springwater.h\"\nint main(void) {\n",
    );
    for (name, fields) in &header.structs {
        c += &format!("  printf(\"struct {name} %zu\\n\", sizeof({name}));\n");
        for (field, _) in fields {
            c += &format!(
                "  printf(\"field {name}.{field} %zu %zu\\n\", offsetof({name}, {field}), \
                 sizeof((({name} *)0)->{field}));\n"
            );
        }
    }
    for constant in &header.constants {
        c += &format!("  printf(\"const {constant} %lld\\n\", (long long)({constant}));\n");
    }
    c + "  return 0;\n}\n"
}

/// Compiles and runs the C layout program against the header in `include`.
fn c_layout(header: &Header, include: &Path, dir: &Path) -> String {
    let source = dir.join("layout.c");
    std::fs::write(&source, c_layout_program(header)).unwrap();
    let exe = dir.join("layout-c");
    let out = Command::new("cc")
        .args(["-std=c11", "-Wall", "-Werror", "-I"])
        .arg(include)
        .arg(&source)
        .arg("-o")
        .arg(&exe)
        .output()
        .expect("cc runs (install a C compiler)");
    assert_ok(&out, "compiling the C layout program");
    let out = Command::new(&exe).output().unwrap();
    assert_ok(&out, "the C layout program");
    String::from_utf8(out.stdout).unwrap()
}

/// Every disagreement between the header (`header`, and the C compiler's `c` layout) and
/// the C# declarations (`csharp`, Layout.cs's output), one line each.
fn drift(header: &Header, c: &str, csharp: &str) -> Vec<String> {
    let mut problems = Vec::new();
    let table = |text: &str, kind: &str| -> HashMap<String, String> {
        text.lines()
            .filter_map(|l| l.strip_prefix(kind))
            .filter_map(|l| l.split_once(' '))
            .map(|(k, v)| (k.to_string(), v.trim_end().to_string()))
            .collect()
    };
    let functions = table(csharp, "fn ");
    for (name, ret, params) in &header.functions {
        let mut want = vec![csharp_type(ret, &header.aliases, true)];
        want.extend(
            params
                .iter()
                .map(|p| csharp_type(p, &header.aliases, false)),
        );
        match functions.get(name) {
            None => problems.push(format!("Native has no {name}")),
            Some(got) if *got != want.join(" ") => problems.push(format!(
                "Native.{name} is `{got}`, the header says `{}`",
                want.join(" ")
            )),
            Some(_) => {}
        }
    }
    for name in functions.keys() {
        if !header.functions.iter().any(|(n, ..)| n == name) {
            problems.push(format!("Native.{name} is not in the header"));
        }
    }
    for kind in ["struct ", "const "] {
        let (want, got) = (table(c, kind), table(csharp, kind));
        for (name, value) in &want {
            match got.get(name) {
                None => problems.push(format!("the C# has no {kind}{name}")),
                Some(v) if v != value => problems.push(format!("{kind}{name}: C# {v}, C {value}")),
                Some(_) => {}
            }
        }
        for name in got.keys().filter(|n| !want.contains_key(*n)) {
            problems.push(format!("{kind}{name} is in the C# but not in the header"));
        }
    }
    let (c_fields, cs_fields) = (table(c, "field "), table(csharp, "field "));
    for (name, fields) in &header.structs {
        for (field, c_type) in fields {
            let key = format!("{name}.{field}");
            let want = format!(
                "{} {}",
                c_fields[&key],
                csharp_type(c_type, &header.aliases, false)
            );
            match cs_fields.get(&key) {
                None => problems.push(format!("the C# {name} has no field {field}")),
                Some(got) if *got != want => {
                    problems.push(format!("{key}: C# offset, size, type `{got}`, C `{want}`"))
                }
                Some(_) => {}
            }
        }
    }
    for key in cs_fields.keys().filter(|k| !c_fields.contains_key(*k)) {
        problems.push(format!("field {key} is in the C# but not in the header"));
    }
    problems.sort();
    problems
}

/// Layout.cs's report of the package's declarations.
fn csharp_layout() -> &'static str {
    static LAYOUT: OnceLock<String> = OnceLock::new();
    LAYOUT.get_or_init(|| {
        let dir = scratch("layout");
        let exe = dir.join("layout.exe");
        mcs(&exe, &[], &[test_source("Layout.cs")]);
        let out = mono(&exe, &[]);
        assert_ok(&out, "Layout.cs");
        String::from_utf8(out.stdout).unwrap()
    })
}

#[test]
fn the_csharp_declarations_match_the_header() {
    if !have_mono() {
        return;
    }
    let include = crate_dir().join("include");
    let header = parse_header(&std::fs::read_to_string(include.join("springwater.h")).unwrap());
    assert!(
        header.functions.len() > 60 && header.structs.len() >= 10 && header.constants.len() > 20
    );
    let dir = scratch("header");
    let c = c_layout(&header, &include, &dir);
    let problems = drift(&header, &c, csharp_layout());
    assert!(
        problems.is_empty(),
        "ffi/csharp/Springwater disagrees with ffi/include/springwater.h; update Native.cs or \
         Structs.cs:\n{}",
        problems.join("\n")
    );
}

/// The comparison above finds what the next version of the header adds: a function, a
/// field, a constant.
#[test]
fn the_header_comparison_finds_a_missing_function_field_and_constant() {
    if !have_mono() {
        return;
    }
    let text = std::fs::read_to_string(crate_dir().join("include/springwater.h")).unwrap();
    let grown = text
        .replace(
            "size_t sw_last_error(",
            "SwStatus sw_surface_wave_forces(const struct SwSurface *surface, uint64_t *out);\n\
             size_t sw_last_error(",
        )
        .replace(
            "  float density;\n} SwBuoyancy;",
            "  float density;\n  float surface_tension;\n} SwBuoyancy;",
        )
        .replace(
            "#define SW_SHAPE_HULL 2",
            "#define SW_SHAPE_HULL 2\n#define SW_SHAPE_CAPSULE 3",
        );
    assert_ne!(grown, text);
    let dir = scratch("grown");
    std::fs::write(dir.join("springwater.h"), &grown).unwrap();
    let header = parse_header(&grown);
    let c = c_layout(&header, &dir, &dir);
    let problems = drift(&header, &c, csharp_layout());
    for expected in [
        "Native has no sw_surface_wave_forces",
        "the C# SwBuoyancy has no field surface_tension",
        "the C# has no const SW_SHAPE_CAPSULE",
        "struct SwBuoyancy: C# 12, C 16",
    ] {
        assert!(
            problems.iter().any(|p| p.contains(expected)),
            "`{expected}` not among {problems:#?}"
        );
    }
    assert_eq!(problems.len(), 4, "{problems:#?}");
}

// ---- The Unity package ----

fn json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{} is not JSON: {e}", path.display()))
}

/// The package's files where Unity looks for them: `package.json` at the root, the runtime
/// assembly's definition beside its sources, the sample's, and a folder per platform for
/// the native library. (Unity itself is not here: this is the layout, not an import.)
#[test]
fn the_unity_package_has_its_layout() {
    let root = package_dir();
    let package = json(&root.join("package.json"));
    let name = package["name"]
        .as_str()
        .expect("package.json names the package");
    assert!(
        name.starts_with("com.")
            && name
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '.' || c == '-'),
        "a Unity package name is lower-case reverse-domain: {name}"
    );
    assert_eq!(
        package["version"],
        env!("CARGO_PKG_VERSION"),
        "the C ABI's version"
    );
    for key in ["displayName", "description", "unity"] {
        assert!(package[key].is_string(), "package.json has no {key}");
    }
    let samples = package["samples"]
        .as_array()
        .expect("package.json lists its samples");
    for sample in samples {
        let path = root.join(sample["path"].as_str().unwrap());
        assert!(
            path.is_dir(),
            "the sample folder {} is missing",
            path.display()
        );
        assert!(sample["path"].as_str().unwrap().starts_with("Samples~/"));
    }

    let runtime = json(&root.join("Springwater/Springwater.asmdef"));
    assert_eq!(runtime["name"], "Springwater");
    assert_eq!(
        runtime["allowUnsafeCode"], true,
        "the bindings use pointers"
    );
    let sample = json(&root.join("Samples~/FloatingWater/Springwater.Samples.asmdef"));
    assert_eq!(sample["references"][0], "Springwater");

    for platform in [
        "Linux/x86_64",
        "Windows/x86_64",
        "macOS",
        "Android/arm64-v8a",
        "iOS",
    ] {
        assert!(
            root.join("Plugins").join(platform).is_dir(),
            "Plugins/{platform} is missing"
        );
    }
    // Unity compiles every .cs it sees: the tests and the sample hide in `~` folders, and
    // the only C# outside them is the runtime's.
    for entry in std::fs::read_dir(&root).unwrap() {
        let path = entry.unwrap().path();
        let file = path.file_name().unwrap().to_str().unwrap().to_string();
        if path.is_dir() && !file.ends_with('~') && !file.starts_with('.') {
            assert!(
                ["Springwater", "Plugins"].contains(&file.as_str()),
                "Unity would import the folder {file}"
            );
        }
    }
}

/// The runtime sources and the sample MonoBehaviour compile against stand-ins for the
/// UnityEngine API they use, with the scripting defines of a current Unity, of one before
/// Span (2020), and of an iOS player (the static library through `__Internal`).
#[test]
fn the_package_and_its_sample_compile_against_unity_stubs() {
    if !have_mono() {
        return;
    }
    let dir = scratch("unity");
    let sample = package_dir().join("Samples~/FloatingWater/FloatingWater.cs");
    for (label, defines) in [
        (
            "unity6",
            "UNITY_5_3_OR_NEWER;UNITY_2021_2_OR_NEWER;UNITY_6000_0_OR_NEWER",
        ),
        ("unity2020", "UNITY_5_3_OR_NEWER"),
        ("ios", "UNITY_5_3_OR_NEWER;UNITY_2021_2_OR_NEWER;UNITY_IOS"),
    ] {
        // As Unity builds them: the runtime's assembly (Springwater.asmdef), then the
        // sample's, which sees only what the runtime makes public.
        let define = format!("-define:{defines}");
        let runtime = dir.join(format!("Springwater-{label}.dll"));
        mcs(&runtime, &["-target:library", &define], &[]);
        let out = dir.join(format!("Samples-{label}.dll"));
        let reference = format!("-r:{}", runtime.display());
        mcs_only(
            &out,
            &["-target:library", &define, &reference],
            &[sample.clone(), test_source("UnityStubs.cs")],
        );
        assert!(out.exists(), "{label}");
    }
}

/// The README's example, taken from the README, compiled and run: it prints a height and
/// the library's message for a refused drop.
#[test]
fn the_readme_csharp_example_compiles_and_runs() {
    if !have_mono() {
        return;
    }
    let readme = std::fs::read_to_string(package_dir().join("README.md")).unwrap();
    let start = readme.find("```csharp\n").expect("a C# example") + "```csharp\n".len();
    let end = start + readme[start..].find("```").unwrap();
    let dir = scratch("readme");
    let source = dir.join("example.cs");
    std::fs::write(&source, &readme[start..end]).unwrap();
    let exe = dir.join("example.exe");
    mcs(&exe, &[], &[source]);
    let out = mono(&exe, &[]);
    assert_ok(&out, "the README's C# example");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("height at (40, 32): "), "{stdout}");
    assert!(
        stdout.contains("refused: drop x = NaN is invalid"),
        "the library's message: {stdout}"
    );
}
