//! `include/springwater.h` is what cbindgen makes of this crate today: the header C users
//! include never drifts from the ABI. After an intended change, regenerate it with
//! `SPRINGWATER_BLESS=1 cargo test -p springwater-ffi --test header` and review its diff.

use std::path::Path;

#[test]
fn the_checked_in_header_is_what_cbindgen_generates() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen parses the crate");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).unwrap();
    // cbindgen found the crate's functions: an empty header cannot pass, nor be blessed.
    let functions = generated
        .lines()
        .filter(|l| !l.starts_with("//") && l.contains(" sw_") && l.contains('('))
        .count();
    assert!(
        functions >= 70,
        "cbindgen declared only {functions} functions"
    );

    let path = dir.join("include").join("springwater.h");
    if std::env::var_os("SPRINGWATER_BLESS").is_some() {
        std::fs::write(&path, &generated).unwrap();
        return;
    }
    let checked_in = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (bless it first)", path.display()));
    assert!(
        checked_in == generated,
        "ffi/include/springwater.h is out of date with ffi/src: regenerate it with \
         `SPRINGWATER_BLESS=1 cargo test -p springwater-ffi --test header` and review the diff"
    );
}
