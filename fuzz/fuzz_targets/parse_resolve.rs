//! Fuzz target: `gcs_lang::load` must never panic, overflow the stack or hang on any bytes.

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (_source, model, diags) = gcs_lang::load("fuzz.gcs", data);
    let errors = diags.iter().any(|d| d.is_error());
    assert_eq!(
        model.is_some(),
        !errors,
        "model returned iff there is no error"
    );
    for d in &diags {
        let s = d.primary.span;
        assert!(
            s.start <= s.end && s.end <= data.len(),
            "span {s:?} outside the input"
        );
    }
});
