#![no_main]

libfuzzer_sys::fuzz_target!(|bytes: &[u8]| embray_fuzz::read(embray::fuzz::Reader::SdfVol, bytes));
