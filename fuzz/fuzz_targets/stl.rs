//! The STL loader (binary and ASCII) on arbitrary bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = rastty::scene::stl::parse(data, "fuzz.stl");
});
