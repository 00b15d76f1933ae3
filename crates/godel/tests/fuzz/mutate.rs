//! Mutations of TOML texts (scenes, settings, scripts) and of binary files (data files): a
//! value replaced by an extreme or a value of the wrong type, a line deleted, duplicated or
//! moved, an unknown field or a table header inserted, lines spliced from another file,
//! truncation, flipped bytes. Each mutation is described in one line, so that a failing
//! case says how it was made.

use crate::gen::Gen;

/// Applies 1 to 3 random text mutations to `text`; returns the result and what was done.
/// `donors` are other texts lines may be taken from.
pub fn text(g: &mut Gen, text: &str, donors: &[String]) -> (String, Vec<String>) {
    let mut t = text.to_string();
    let mut log = Vec::new();
    for _ in 0..g.pick(&[1, 1, 1, 2, 2, 3]) {
        let (next, what) = one(g, &t, donors);
        t = next;
        log.push(what);
    }
    (t, log)
}

/// Byte spans of the values after `=` on each line (up to a comment or the line's end).
fn value_spans(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for line in text.split_inclusive('\n') {
        if let Some(eq) = line.find('=') {
            let rest = &line[eq + 1..];
            let end = rest.find('#').unwrap_or(rest.trim_end_matches('\n').len());
            if !rest[..end].trim().is_empty() {
                out.push((start + eq + 1, start + eq + 1 + end));
            }
        }
        start += line.len();
    }
    out
}

/// Byte spans of the numbers in `text` (also inside inline tables and arrays).
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit()
            || ((b[i] == b'-' || b[i] == b'+') && i + 1 < b.len() && b[i + 1].is_ascii_digit());
        let after_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        if starts && !after_word {
            let s = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b".+-_".contains(&b[i])) {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Byte spans of the basic strings in `text`, quotes included.
fn string_spans(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut open = None;
    for (i, c) in text.char_indices() {
        if c == '\n' {
            open = None;
        } else if c == '"' {
            match open {
                None => open = Some(i),
                Some(s) => {
                    out.push((s, i + 1));
                    open = None;
                }
            }
        }
    }
    out
}

fn replace(text: &str, (s, e): (usize, usize), with: &str) -> String {
    format!("{}{}{}", &text[..s], with, &text[e..])
}

/// The largest char boundary ≤ i.
fn boundary(text: &str, mut i: usize) -> usize {
    i = i.min(text.len());
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Strings that make names, kinds and paths odd.
const STRINGS: [&str; 18] = [
    "\"\"",
    "\" \"",
    "\".\"",
    "\"..\"",
    "\"-x\"",
    "\"a/b\"",
    "\"../../etc/passwd\"",
    "\"/dev/zero\"",
    "\"\\u0000\"",
    "\"line\\nbreak\"",
    "\"tab\\there\"",
    "\"earth\"",
    "\"exact\"",
    "\"coordinates\"",
    "\"plane\"",
    "\"image\"",
    "\"ÄÖÜ€\"",
    "'''multi\nline'''",
];

/// Field names: known ones in the wrong places, and unknown ones.
const KEYS: [&str; 16] = [
    "bogus",
    "radius",
    "name",
    "width",
    "kind",
    "a",
    "metric",
    "max_past",
    "speed",
    "frames",
    "shaders",
    "objects",
    "temperature",
    "lamps",
    "data",
    "texture",
];

const HEADERS: [&str; 12] = [
    "[camera]",
    "[[object]]",
    "[[light]]",
    "[observer]",
    "[trace]",
    "[spacetime]",
    "[settings]",
    "[[keyframe]]",
    "[time]",
    "[light]",
    "[objects.o0]",
    "[bogus]",
];

fn one(g: &mut Gen, t: &str, donors: &[String]) -> (String, String) {
    let lines: Vec<&str> = t.split_inclusive('\n').collect();
    let line = |g: &mut Gen| g.index(lines.len());
    match g.index(16) {
        14 | 15 => {
            // A mild change that often keeps the file valid: a number scaled or its sign flipped.
            let spans: Vec<(usize, usize)> = number_spans(t)
                .into_iter()
                .filter(|&(a, b)| t[a..b].parse::<f64>().is_ok())
                .collect();
            if spans.is_empty() {
                return one(g, t, donors);
            }
            let sp = g.pick(&spans);
            let old = &t[sp.0..sp.1];
            let k = g.pick(&[-1.0, 0.5, 2.0, 10.0, 1e-3, 1.0 + 1e-12, 1.0 - 1e-12]);
            let with = match old.parse::<i64>() {
                Ok(i) => ((i as f64 * k).round() as i64).to_string(),
                Err(_) => crate::gen::num(old.parse::<f64>().unwrap_or(0.0) * k),
            };
            let what = format!("number `{old}` at byte {} -> `{with}`", sp.0);
            (replace(t, sp, &with), what)
        }
        0..=2 => {
            let spans = number_spans(t);
            if spans.is_empty() {
                return one(g, &format!("{t}x = 1\n"), donors);
            }
            let sp = g.pick(&spans);
            let with = g.extreme();
            let what = format!("number `{}` at byte {} -> `{with}`", &t[sp.0..sp.1], sp.0);
            (replace(t, sp, &with), what)
        }
        3 => {
            let spans = value_spans(t);
            if spans.is_empty() {
                return (format!("{t}\n"), "newline appended".into());
            }
            let sp = g.pick(&spans);
            let with = format!(" {}", g.extreme());
            let what = format!("value `{}` -> `{with}`", t[sp.0..sp.1].trim());
            (replace(t, sp, &with), what)
        }
        4 => {
            let spans = string_spans(t);
            if spans.is_empty() {
                return (format!("{t}name = \"\"\n"), "name appended".into());
            }
            let sp = g.pick(&spans);
            let with = g.pick(&STRINGS);
            let what = format!("string {} -> {with}", &t[sp.0..sp.1]);
            (replace(t, sp, with), what)
        }
        5 => {
            let i = line(g);
            let out: String = lines
                .iter()
                .enumerate()
                .filter(|(k, _)| *k != i)
                .map(|(_, l)| *l)
                .collect();
            (out, format!("line {} deleted", i + 1))
        }
        6 => {
            let i = line(g);
            let mut out: Vec<&str> = lines.clone();
            if let Some(l) = lines.get(i) {
                out.insert(i, l);
            }
            (out.concat(), format!("line {} duplicated", i + 1))
        }
        7 => {
            let (i, j) = (line(g), line(g));
            let mut out: Vec<&str> = lines.clone();
            if i < out.len() {
                let l = out.remove(i);
                out.insert(j.min(out.len()), l);
            }
            (out.concat(), format!("line {} moved to {}", i + 1, j + 1))
        }
        8 => {
            let i = line(g);
            let key = g.pick(&KEYS);
            let v = g.extreme();
            let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            out.insert(i.min(out.len()), format!("{key} = {v}\n"));
            (
                out.concat(),
                format!("`{key} = {v}` inserted at line {}", i + 1),
            )
        }
        9 => {
            let i = line(g);
            let h = g.pick(&HEADERS);
            let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            out.insert(i.min(out.len()), format!("{h}\n"));
            (out.concat(), format!("`{h}` inserted at line {}", i + 1))
        }
        10 if !donors.is_empty() => {
            let d = g.pick(donors);
            let dl: Vec<&str> = d.split_inclusive('\n').collect();
            let (a, n) = (g.index(dl.len()), g.int(1, 4) as usize);
            let piece: String = dl[a..(a + n).min(dl.len())].concat();
            let i = line(g);
            let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            out.insert(i.min(out.len()), piece.clone());
            (
                out.concat(),
                format!("{:?} spliced in at line {}", piece, i + 1),
            )
        }
        11 => {
            let at = boundary(t, g.index(t.len() + 1));
            (t[..at].to_string(), format!("truncated to {at} bytes"))
        }
        _ => {
            // Flipped bytes, the result made valid UTF-8 (text APIs take &str).
            let mut b = t.as_bytes().to_vec();
            let mut what = Vec::new();
            for _ in 0..g.int(1, 3) {
                if b.is_empty() {
                    break;
                }
                let i = g.index(b.len());
                let v = if g.chance(0.5) {
                    b[i] ^ (1 << g.int(0, 7))
                } else {
                    g.byte()
                };
                what.push(format!("byte {i} {:#04x} -> {v:#04x}", b[i]));
                b[i] = v;
            }
            (String::from_utf8_lossy(&b).into_owned(), what.join(", "))
        }
    }
}

/// Applies 1 to 4 random byte mutations to `bytes`; returns the result and what was done.
pub fn bytes(g: &mut Gen, bytes: &[u8]) -> (Vec<u8>, Vec<String>) {
    let mut b = bytes.to_vec();
    let mut log = Vec::new();
    for _ in 0..g.pick(&[1, 1, 2, 3, 4]) {
        let n = b.len();
        let at = g.index(n + 1);
        match g.index(9) {
            0 | 1 => {
                if n > 0 {
                    let i = at.min(n - 1);
                    let v = if g.chance(0.5) {
                        b[i] ^ (1 << g.int(0, 7))
                    } else {
                        g.byte()
                    };
                    log.push(format!("byte {i} {:#04x} -> {v:#04x}", b[i]));
                    b[i] = v;
                }
            }
            2 => {
                // a 4-byte field (sizes, offsets, counts in the EXR header) set to an extreme
                if n >= 4 {
                    let i = at.min(n - 4);
                    let v: u32 =
                        g.pick(&[0, 1, 0x7fff_ffff, 0xffff_ffff, 0x8000_0000, 0xffff, 1 << 24]);
                    log.push(format!("u32 at {i} -> {v:#x}"));
                    b[i..i + 4].copy_from_slice(&v.to_le_bytes());
                }
            }
            3 => {
                if n >= 8 {
                    let i = at.min(n - 8);
                    let v: u64 = g.pick(&[0, u64::MAX, i64::MAX as u64, 1 << 40, n as u64 * 2]);
                    log.push(format!("u64 at {i} -> {v:#x}"));
                    b[i..i + 8].copy_from_slice(&v.to_le_bytes());
                }
            }
            4 => {
                log.push(format!("truncated to {at} bytes"));
                b.truncate(at);
            }
            5 => {
                let k = g.int(1, 64) as usize;
                let extra: Vec<u8> = (0..k).map(|_| g.byte()).collect();
                log.push(format!("{k} random bytes inserted at {at}"));
                b.splice(at..at, extra);
            }
            6 => {
                let k = (g.int(1, 256) as usize).min(n - at.min(n));
                log.push(format!("{k} bytes deleted at {at}"));
                b.drain(at..at + k);
            }
            7 => {
                // a piece of the file repeated
                let k = (g.int(1, 512) as usize).min(n - at.min(n));
                let piece = b[at..at + k].to_vec();
                let to = g.index(b.len() + 1);
                log.push(format!("{k} bytes from {at} copied to {to}"));
                b.splice(to..to, piece);
            }
            _ => {
                let k = g.int(1, 4096) as usize;
                log.push(format!("{k} zero bytes appended"));
                b.extend(std::iter::repeat_n(0u8, k));
            }
        }
    }
    (b, log)
}
