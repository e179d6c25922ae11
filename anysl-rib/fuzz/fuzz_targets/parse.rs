//! Feeds arbitrary bytes (plain or gzip-compressed RIB) to the reader: it must not panic or hang.
#![no_main]

use anysl_rib::{parse_bytes, Options, Recorder};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let options = Options { max_requests: 100_000, ..Options::default() };
    let mut recorder = Recorder::new();
    match parse_bytes("fuzz.rib", data, &mut recorder, &options) {
        Ok(report) => drop(report.render_warnings()),
        Err(e) => drop(e.render()),
    }
});
