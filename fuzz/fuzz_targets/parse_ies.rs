#![no_main]
//! IES parser, conversion to the EULUMDAT model and the IES writer.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(lum) = goniolight::photometry::Luminaire::from_bytes("fuzz.ies", data) {
        let _ = lum.summary();
        let _ = goniolight::photometry::ies::write_ies(&lum.data);
    }
});
