//! An OBJ quad whose MTL file and texture are the fuzzer's bytes (the MTL
//! text before the first NUL, the image after it), written beside it in a
//! directory of this process's own: `mtllib`, `map_Kd` and the decoder.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;

const OBJ: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3 4/4\n";

fn dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("rastty-fuzz-mtl-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("q.obj"), OBJ).unwrap();
        d
    })
}

fuzz_target!(|data: &[u8]| {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let d = dir();
    std::fs::write(d.join("m.mtl"), &data[..split]).unwrap();
    std::fs::write(d.join("t.png"), data.get(split + 1..).unwrap_or(&[])).unwrap();
    let options = rastty::scene::LoadOptions::default();
    let _ = rastty::scene::obj::load(&d.join("q.obj"), &options);
});
