//! Robustness: `Scene::from_str` returns `Ok` or `Err` for any input and never panics —
//! random strings, and the shipped scene texts mutated by byte flips, deleted or duplicated
//! lines, and numbers replaced by random floats (NaN, ±inf, negatives, huge, tiny).
//! Errors must also carry a sane location (line and column within the text).

use proptest::prelude::*;
use scene::{Scene, SceneError};

fn good_texts() -> Vec<String> {
    let mut texts: Vec<String> = testkit::toml_files(&testkit::scenes_dir())
        .into_iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    texts.sort();
    texts
}

fn check(text: &str) {
    match Scene::from_str(text, "fuzz.toml") {
        Ok(s) => {
            // A scene that is accepted must be fully valid.
            assert!(s.trace.max_past > 0.0 && s.trace.max_past.is_finite());
            for o in &s.objects {
                assert!(o.temperature > 0.0 && o.temperature.is_finite());
            }
            let (w, h) = (s.camera.width(), s.camera.height());
            assert!(w >= 1 && h >= 1);
            assert!(s.camera.pixel_direction(w / 2, h / 2).is_some());
        }
        Err(e) => {
            let shown = e.to_string();
            assert!(!shown.contains(['\n', '\r']), "not one line: {shown:?}");
            let SceneError { location, .. } = e;
            if let Some(l) = location {
                let lines = text.split('\n').count();
                assert!(l.line >= 1 && l.line <= lines, "line {} of {lines}", l.line);
                assert!(l.column >= 1);
            }
        }
    }
}

/// A replacement for a number: ordinary, extreme, or not a number at all.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|v| format!("{v:?}")),
        (-1e3f64..1e3).prop_map(|v| format!("{v:?}")),
        any::<i64>().prop_map(|v| v.to_string()),
        Just("nan".to_string()),
        Just("-nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("0".to_string()),
        Just("-0.0".to_string()),
        Just("1e309".to_string()),
        Just("\"1\"".to_string()),
    ]
}

#[derive(Debug, Clone)]
enum Mutation {
    FlipByte(usize, u8),
    DeleteLine(usize),
    DuplicateLine(usize),
    ReplaceNumber(usize, String),
    Truncate(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::FlipByte(i, b)),
        any::<usize>().prop_map(Mutation::DeleteLine),
        any::<usize>().prop_map(Mutation::DuplicateLine),
        (any::<usize>(), number()).prop_map(|(i, n)| Mutation::ReplaceNumber(i, n)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

/// Spans of the numbers in `text` (digits with signs, dots and exponents).
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_digit() {
            let start = if i > 0 && b[i - 1] == b'-' { i - 1 } else { i };
            let mut j = i;
            while j < b.len()
                && (b[j].is_ascii_digit() || matches!(b[j], b'.' | b'e' | b'E' | b'-' | b'+'))
            {
                j += 1;
            }
            out.push((start, j));
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

fn apply(text: &str, m: &Mutation) -> String {
    let lines: Vec<&str> = text.split('\n').collect();
    match m {
        Mutation::FlipByte(i, b) => {
            let mut bytes = text.as_bytes().to_vec();
            if !bytes.is_empty() {
                let k = i % bytes.len();
                bytes[k] = *b;
            }
            // Invalid UTF-8 cannot reach `from_str`; keep what survives lossy decoding.
            String::from_utf8_lossy(&bytes).into_owned()
        }
        Mutation::DeleteLine(i) => {
            let k = i % lines.len();
            let mut l = lines.clone();
            l.remove(k);
            l.join("\n")
        }
        Mutation::DuplicateLine(i) => {
            let k = i % lines.len();
            let mut l = lines.clone();
            l.insert(k, lines[k]);
            l.join("\n")
        }
        Mutation::ReplaceNumber(i, n) => {
            let spans = number_spans(text);
            if spans.is_empty() {
                return text.to_string();
            }
            let (a, b) = spans[i % spans.len()];
            format!("{}{}{}", &text[..a], n, &text[b..])
        }
        Mutation::Truncate(i) => {
            let mut k = i % (text.len() + 1);
            while !text.is_char_boundary(k) {
                k -= 1;
            }
            text[..k].to_string()
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn random_strings_never_panic(s in "\\PC{0,200}") {
        check(&s);
    }

    #[test]
    fn toml_like_strings_never_panic(s in "([a-z_\\[\\]{}=\",.0-9 -]{0,30}\n){0,12}") {
        check(&s);
    }

    #[test]
    fn mutated_scenes_never_panic(which in any::<usize>(), ms in prop::collection::vec(mutation(), 1..4)) {
        let texts = good_texts();
        let mut text = texts[which % texts.len()].clone();
        for m in &ms {
            text = apply(&text, m);
        }
        check(&text);
    }
}

/// Fuzzing found messages of two lines: serde quotes an unknown variant as written, so
/// `kind = "line\nbreak"` put a line break into the message. Every message is one line,
/// with control characters escaped, in the file name and field path too.
#[test]
fn regression_fuzz_scene_errors_are_one_line() {
    let text = "name = \"x\"\n[camera]\nkind = \"line\\nbreak\"\nwidth = 1\nheight = 1\n";
    let e = Scene::from_str(text, "odd\nname.toml").unwrap_err();
    assert_eq!(
        e.to_string(),
        "odd\\nname.toml:3:8: camera.kind: unknown variant `line\\nbreak`, expected one of `pinhole`, `panorama`, `sphere`, `fisheye`"
    );
    let e = Scene::from_str("\"a\\tb\" = 1\n", "x.toml").unwrap_err();
    assert!(!e.to_string().contains('\t'), "{e}");
    assert!(e.to_string().contains("a\\tb"), "{e}");
}

#[test]
fn every_number_replaced_by_each_extreme_value() {
    // Deterministic sweep: each number of each good scene, replaced by each nasty value.
    let nasty = [
        "nan",
        "-nan",
        "inf",
        "-inf",
        "-1",
        "0",
        "-0.0",
        "1e308",
        "5e-324",
        "99999999999",
        "-1e300",
    ];
    for text in good_texts() {
        for (a, b) in number_spans(&text) {
            for n in nasty {
                check(&format!("{}{}{}", &text[..a], n, &text[b..]));
            }
        }
    }
}

#[test]
fn deeply_nested_input_does_not_overflow_the_stack() {
    for depth in [1_000, 100_000] {
        check(&format!(
            "name = {}{}",
            "[".repeat(depth),
            "]".repeat(depth)
        ));
        check(&format!("name = {}", "{ a = ".repeat(depth)));
        check(&format!("x = {}1{}", "[".repeat(depth), "]".repeat(depth)));
    }
}
