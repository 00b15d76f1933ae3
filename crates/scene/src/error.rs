//! Located scene-file errors: [`SceneError`] names the file, line, column and field path,
//! e.g. `scenes/x.toml:12:10: object[1].radius: must be positive, got -1`.
//!
//! Positions come from the spanned TOML tree ([`Locator`]): serde errors carry a byte span
//! that is mapped back to a field path, and validation errors carry a field path that is
//! mapped forward to the byte span of that value (or of its nearest existing ancestor, when
//! the field itself is missing).

use std::fmt;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// A 1-based line and column (columns count characters, not bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Location {
    pub line: usize,
    pub column: usize,
}

/// A scene-file error: where it is and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// The file as given by the caller (a path, or a name such as `<builtin>`).
    pub file: String,
    /// Line and column, when the error has a place in the text (not for unreadable files).
    pub location: Option<Location>,
    /// Field path such as `object[1].radius` (objects and lights counted from 0); empty for
    /// errors about the document as a whole (syntax errors at top level, unreadable file).
    pub field: String,
    pub message: String,
}

impl SceneError {
    /// Line number (1-based), if located.
    pub fn line(&self) -> Option<usize> {
        self.location.map(|l| l.line)
    }
    /// Column number (1-based), if located.
    pub fn column(&self) -> Option<usize> {
        self.location.map(|l| l.column)
    }
}

impl fmt::Display for SceneError {
    /// One line, whatever the input: control characters that come from the file (a key or a
    /// value quoted in a message, an odd file name) are written escaped, e.g. `\n`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", one_line(&self.file))?;
        if let Some(l) = self.location {
            write!(f, ":{}:{}", l.line, l.column)?;
        }
        if !self.field.is_empty() {
            write!(f, ": {}", one_line(&self.field))?;
        }
        write!(f, ": {}", one_line(&self.message))
    }
}

/// `text` with its control characters escaped (a line break becomes `\n`), for messages
/// that quote what a user wrote and must stay one line.
pub fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

impl std::error::Error for SceneError {}

/// Converts a byte offset into a 1-based line and column. Offsets past the end (or inside a
/// multi-byte character) are clamped, so any offset is safe.
pub fn line_column(text: &str, offset: usize) -> Location {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = text[line_start..offset].chars().count() + 1;
    Location { line, column }
}

/// One step of a field path.
#[derive(Clone, Debug, PartialEq)]
enum Segment {
    Key(String),
    Index(usize),
}

/// Splits `object[1].texture.path` into segments. Keys in our schema never contain `.` or `[`.
fn parse_path(path: &str) -> Vec<Segment> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let mut pieces = part.split('[');
        if let Some(key) = pieces.next() {
            if !key.is_empty() {
                out.push(Segment::Key(key.to_string()));
            }
        }
        for idx in pieces {
            if let Ok(i) = idx.trim_end_matches(']').parse() {
                out.push(Segment::Index(i));
            }
        }
    }
    out
}

fn format_path(segments: &[Segment]) -> String {
    let mut s = String::new();
    for seg in segments {
        match seg {
            Segment::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Segment::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// Maps between field paths and places in one scene text, using its spanned TOML tree.
pub struct Locator<'a> {
    file: &'a str,
    text: &'a str,
    root: Option<&'a Spanned<DeTable<'a>>>,
}

impl<'a> Locator<'a> {
    pub fn new(file: &'a str, text: &'a str, root: Option<&'a Spanned<DeTable<'a>>>) -> Self {
        Locator { file, text, root }
    }

    /// An error at a byte span; the field path is recovered from the tree.
    pub fn at_span(
        &self,
        span: Option<std::ops::Range<usize>>,
        message: impl Into<String>,
    ) -> SceneError {
        let field = match (&span, self.root) {
            // Missing-field errors span the whole table that lacks the field: name the table.
            (Some(s), Some(root)) if root.span() == *s => String::new(),
            (Some(s), Some(root)) => {
                format_path(&path_of_span(self.text, root.get_ref(), s.clone()))
            }
            _ => String::new(),
        };
        SceneError {
            file: self.file.to_string(),
            location: span.map(|s| line_column(self.text, s.start)),
            field,
            message: message.into(),
        }
    }

    /// An error about the value at `path` (located at that value, or at its nearest existing
    /// ancestor when the value itself is absent, e.g. a missing required field).
    pub fn at_path(&self, path: &str, message: impl Into<String>) -> SceneError {
        let span = self.root.map(|root| span_of_path(root, &parse_path(path)));
        SceneError {
            file: self.file.to_string(),
            location: span.map(|s| line_column(self.text, s.start)),
            field: path.to_string(),
            message: message.into(),
        }
    }
}

/// The 1-based line of the value at `path` (such as `keyframe[2].settings.exposure`) in the
/// TOML `text`, or of its nearest existing ancestor; `None` if the text does not parse.
pub fn line_of_path(text: &str, path: &str) -> Option<usize> {
    let root = DeTable::parse(text).ok()?;
    Some(line_column(text, span_of_path(&root, &parse_path(path)).start).line)
}

fn span_of_path(root: &Spanned<DeTable<'_>>, path: &[Segment]) -> std::ops::Range<usize> {
    let mut span = root.span();
    // The document root's span starts at 0; a missing top-level table is best reported at
    // the start of the file, which it already is.
    let mut node: Option<&DeValue<'_>> = None;
    let mut table: Option<&DeTable<'_>> = Some(root.get_ref());
    for seg in path {
        let next = match (seg, table, node) {
            (Segment::Key(k), Some(t), _) => {
                t.iter().find(|(key, _)| key.get_ref() == k).map(|(_, v)| v)
            }
            (Segment::Index(i), None, Some(DeValue::Array(a))) => a.get(*i),
            _ => None,
        };
        let Some(v) = next else { break };
        span = v.span();
        node = Some(v.get_ref());
        table = match v.get_ref() {
            DeValue::Table(t) => Some(t),
            _ => None,
        };
    }
    span
}

fn contains(span: std::ops::Range<usize>, offset: usize) -> bool {
    span.start <= offset && offset < span.end.max(span.start + 1)
}

/// The field whose value spans exactly `span` (a table lacking a field), else the deepest
/// field whose key or value contains its start; failing that (an error between
/// fields, such as a duplicate key), the `[table]` or `[[array]]` header above it.
/// Header tables span only their header, so the whole tree is searched, with an explicit
/// stack because input nesting is unbounded.
fn path_of_span(text: &str, root: &DeTable<'_>, target: std::ops::Range<usize>) -> Vec<Segment> {
    let offset = target.start;
    let mut exact: Option<Vec<Segment>> = None;
    let mut best: Vec<Segment> = Vec::new();
    let mut header: (usize, Vec<Segment>) = (0, Vec::new());
    let mut stack: Vec<(Vec<Segment>, &DeTable<'_>)> = vec![(Vec::new(), root)];
    let mut arrays: Vec<(Vec<Segment>, &[Spanned<DeValue<'_>>])> = Vec::new();
    loop {
        // Children of one table or array: (path, whether its key holds the offset, value).
        let mut children: Vec<(Vec<Segment>, bool, &Spanned<DeValue<'_>>)> = Vec::new();
        if let Some((path, table)) = stack.pop() {
            for (k, v) in table.iter() {
                let mut p = path.clone();
                p.push(Segment::Key(k.get_ref().to_string()));
                children.push((p, contains(k.span(), offset), v));
            }
        } else if let Some((path, items)) = arrays.pop() {
            for (i, v) in items.iter().enumerate() {
                let mut p = path.clone();
                p.push(Segment::Index(i));
                children.push((p, false, v));
            }
        } else {
            break;
        }
        for (path, key_hit, v) in children {
            let span = v.span();
            if span == target && exact.as_ref().is_none_or(|e| path.len() > e.len()) {
                exact = Some(path.clone());
            }
            if (key_hit || contains(span.clone(), offset)) && path.len() > best.len() {
                best = path.clone();
            }
            match v.get_ref() {
                DeValue::Table(t) => {
                    let is_header = text.get(span.start..).is_some_and(|s| s.starts_with('['));
                    if is_header && span.start <= offset && span.start >= header.0 {
                        header = (span.start, path.clone());
                    }
                    stack.push((path, t));
                }
                DeValue::Array(a) => arrays.push((path, a)),
                _ => {}
            }
        }
    }
    if let Some(p) = exact {
        p
    } else if best.is_empty() {
        header.1
    } else {
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_column_counts_from_one() {
        let t = "ab\ncdé\nf";
        assert_eq!(line_column(t, 0), Location { line: 1, column: 1 });
        assert_eq!(line_column(t, 3), Location { line: 2, column: 1 });
        assert_eq!(line_column(t, 8), Location { line: 3, column: 1 });
        assert_eq!(line_column(t, 1000), Location { line: 3, column: 2 });
        // Inside the two-byte é: clamped back to its start.
        assert_eq!(line_column(t, 6), Location { line: 2, column: 3 });
    }

    #[test]
    fn paths_round_trip() {
        let p = parse_path("object[1].texture.path");
        assert_eq!(format_path(&p), "object[1].texture.path");
    }

    #[test]
    fn locates_path_and_offset() {
        let text =
            "name = \"x\"\n[[object]]\nname = \"a\"\n[[object]]\nname = \"b\"\nradius = -1\n";
        let root = DeTable::parse(text).unwrap();
        let loc = Locator::new("f.toml", text, Some(&root));
        let e = loc.at_path("object[1].radius", "must be positive, got -1");
        assert_eq!(
            e.to_string(),
            "f.toml:6:10: object[1].radius: must be positive, got -1"
        );
        let off = text.find("-1").unwrap();
        let e = loc.at_span(Some(off..off + 2), "bad");
        assert_eq!(e.field, "object[1].radius");
    }
}
