#![no_main]
//! EULUMDAT parser, then the whole pipeline a loaded file goes through.

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(lum) = goniolight::photometry::Luminaire::from_bytes("fuzz.ldt", data) {
        let _ = lum.summary();
        let _ = lum.data.to_ldt_string();
        let _ = goniolight::photometry::LdtTexture::from_distribution(&lum.distribution);
    }
});
