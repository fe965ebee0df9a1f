//! Fuzz target: STEP string decoding never panics; what the lossy decoder reads survives an
//! encode/decode round trip.
#![no_main]

use libfuzzer_sys::fuzz_target;
use poinav_ifc::string::{decode, decode_lossy, encode};

fuzz_target!(|data: &[u8]| {
    let _ = decode(data);
    let text = decode_lossy(data);
    let encoded = encode(&text);
    assert!(
        encoded.bytes().all(|b| (b' '..=b'~').contains(&b)),
        "encoded strings are printable ASCII"
    );
    assert_eq!(
        decode(encoded.as_bytes()).expect("encoded strings decode"),
        text
    );
});
