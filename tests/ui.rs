//! Compile-time behaviour of `generator!`: grammars that must compile (and run), and
//! mistakes that must be reported with clear messages on the user's own tokens.

#[rustversion::attr(not(stable(1.95)), ignore = "UI snapshots are checked on rustc 1.95")]
#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.pass("tests/ui/pass/*.rs");
    t.compile_fail("tests/ui/fail/*.rs");
}
