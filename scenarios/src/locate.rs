//! Positions in the scenario text: the span of a dotted field path, the field path at a
//! byte offset, and byte offset -> 1-based line/column.

use std::ops::Range;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// One step of a field path: a table key or an array index.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Step {
    Key(String),
    Index(usize),
}

/// A parsed scenario text with the spans of every key and value.
#[derive(Debug)]
pub(crate) struct Document<'t> {
    text: &'t str,
    root: Spanned<DeTable<'t>>,
}

impl<'t> Document<'t> {
    /// Parse `text` (TOML syntax only).
    pub(crate) fn parse(text: &'t str) -> Result<Self, toml::de::Error> {
        Ok(Self {
            text,
            root: DeTable::parse(text)?,
        })
    }

    /// Parse as much of `text` as its syntax allows (to name the field a syntax error
    /// interrupts).
    pub(crate) fn parse_recoverable(text: &'t str) -> Self {
        Self {
            text,
            root: DeTable::parse_recoverable(text).0,
        }
    }

    /// The parsed tree, to deserialize from.
    pub(crate) fn into_root(self) -> Spanned<DeTable<'t>> {
        self.root
    }

    /// The text of `span`, if it lies in the document.
    pub(crate) fn snippet(&self, span: &Range<usize>) -> Option<&'t str> {
        self.text.get(span.clone())
    }

    /// 1-based line and column (characters) of byte `offset`.
    pub(crate) fn position(&self, offset: usize) -> (usize, usize) {
        line_column(self.text, offset)
    }

    /// The span of the value at `path` (`a.b[2].c`); when part of the path is absent, the
    /// span of the deepest part present (a table header), or the document start.
    pub(crate) fn span_of(&self, path: &str) -> Range<usize> {
        match self.deepest(path) {
            (Some(value), _) => value.span(),
            (None, _) => self.root.span(),
        }
    }

    /// The text of the number at `path`, if the whole path exists and holds a number.
    pub(crate) fn number_at(&self, path: &str) -> Option<&'t str> {
        match self.deepest(path) {
            (Some(value), true) => match value.get_ref() {
                DeValue::Integer(_) | DeValue::Float(_) => self.snippet(&value.span()),
                _ => None,
            },
            _ => None,
        }
    }

    /// The deepest value along `path`, and whether it is the whole path.
    fn deepest(&self, path: &str) -> (Option<&Spanned<DeValue<'t>>>, bool) {
        let steps = parse_path(path);
        let mut node: Option<&Spanned<DeValue<'t>>> = None;
        for step in &steps {
            let next = match (node, step) {
                (None, Step::Key(key)) => lookup(self.root.get_ref(), key),
                (Some(value), step) => child(value.get_ref(), step),
                (None, Step::Index(_)) => None,
            };
            match next {
                Some(value) => node = Some(value),
                None => return (node, false),
            }
        }
        (node, true)
    }

    /// The field path whose key or value holds byte `offset` most tightly, with the span
    /// of that value; empty path and the root span when no field does.
    pub(crate) fn path_at(&self, offset: usize) -> (String, Range<usize>) {
        let mut best = Best {
            offset,
            path: Vec::new(),
            span: self.root.span(),
            width: usize::MAX,
        };
        search_table(self.root.get_ref(), &mut Vec::new(), &mut best);
        (format_path(&best.path), best.span)
    }

    /// Whether `span` is the span of the whole document (errors about the top level).
    pub(crate) fn is_root(&self, span: &Range<usize>) -> bool {
        *span == self.root.span()
    }
}

/// The tightest match found so far by [`Document::path_at`].
struct Best {
    offset: usize,
    path: Vec<Step>,
    span: Range<usize>,
    width: usize,
}

impl Best {
    /// Consider `candidate` (a key or value span) for the entry at `path` whose value
    /// spans `value_span`; ties go to the deeper path.
    fn offer(&mut self, candidate: &Range<usize>, path: &[Step], value_span: &Range<usize>) {
        let holds = candidate.contains(&self.offset)
            || (candidate.is_empty() && candidate.start == self.offset);
        let width = candidate.len();
        if holds && (width < self.width || (width == self.width && path.len() > self.path.len())) {
            self.width = width;
            self.path = path.to_vec();
            self.span = value_span.clone();
        }
    }
}

fn search_table(table: &DeTable<'_>, path: &mut Vec<Step>, best: &mut Best) {
    for (key, value) in table.iter() {
        path.push(Step::Key(key.get_ref().to_string()));
        best.offer(&key.span(), path, &value.span());
        search_value(value, path, best);
        path.pop();
    }
}

fn search_value(value: &Spanned<DeValue<'_>>, path: &mut Vec<Step>, best: &mut Best) {
    best.offer(&value.span(), path, &value.span());
    match value.get_ref() {
        DeValue::Table(table) => search_table(table, path, best),
        DeValue::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                path.push(Step::Index(i));
                search_value(item, path, best);
                path.pop();
            }
        }
        _ => {}
    }
}

fn lookup<'a, 't>(table: &'a DeTable<'t>, key: &str) -> Option<&'a Spanned<DeValue<'t>>> {
    table
        .iter()
        .find(|(k, _)| k.get_ref() == key)
        .map(|(_, v)| v)
}

fn child<'a, 't>(value: &'a DeValue<'t>, step: &Step) -> Option<&'a Spanned<DeValue<'t>>> {
    match (value, step) {
        (DeValue::Table(table), Step::Key(key)) => lookup(table, key),
        (DeValue::Array(items), Step::Index(i)) => items.get(*i),
        _ => None,
    }
}

/// `a.b[2].c` -> `[a, b, 2, c]`.
fn parse_path(path: &str) -> Vec<Step> {
    let mut steps = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (key, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
        if !key.is_empty() {
            steps.push(Step::Key(key.to_string()));
        }
        while let Some(open) = rest.strip_prefix('[') {
            let Some(close) = open.find(']') else { break };
            match open[..close].parse() {
                Ok(i) => steps.push(Step::Index(i)),
                Err(_) => break,
            }
            rest = &open[close + 1..];
        }
    }
    steps
}

/// `[a, b, 2, c]` -> `a.b[2].c`.
fn format_path(steps: &[Step]) -> String {
    let mut out = String::new();
    for step in steps {
        match step {
            Step::Key(key) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(key);
            }
            Step::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// 1-based line and column (in characters) of byte `offset` in `text`; offsets past the
/// end or inside a character are moved back to the nearest character start.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |nl| nl + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "name = \"a\"\n[x]\ne = 1.2\n[x.y]\nz = [1, 2, 3]\n\
                        [[ant]]\nname = \"p\"\n[[ant]]\nname = \"é\"\nq = 5\n";

    fn at(doc: &Document<'_>, path: &str) -> (usize, usize) {
        doc.position(doc.span_of(path).start)
    }

    #[test]
    fn spans_of_paths_point_at_values_or_the_nearest_header() {
        let doc = Document::parse(TEXT).unwrap();
        assert_eq!(at(&doc, "name"), (1, 8));
        assert_eq!(at(&doc, "x.e"), (3, 5));
        assert_eq!(at(&doc, "x.y.z"), (5, 5));
        assert_eq!(at(&doc, "x.y.z[2]"), (5, 12));
        assert_eq!(at(&doc, "ant[1].q"), (10, 5));
        assert_eq!(at(&doc, "ant[1]"), (8, 1));
        // Absent key: the enclosing table's header; absent everything: the start.
        assert_eq!(at(&doc, "x.missing"), (2, 1));
        assert_eq!(at(&doc, "nothing.here"), (1, 1));
        assert_eq!(doc.snippet(&doc.span_of("x.e")), Some("1.2"));
        assert_eq!(doc.number_at("x.e"), Some("1.2"));
        assert_eq!(doc.number_at("x.y.z[1]"), Some("2"));
        assert_eq!(doc.number_at("x.y.z"), None); // an array
        assert_eq!(doc.number_at("name"), None); // a string
        assert_eq!(doc.number_at("x.e.f"), None); // not the whole path
    }

    #[test]
    fn path_at_finds_the_tightest_field() {
        let doc = Document::parse(TEXT).unwrap();
        let offset = TEXT.find("1.2").unwrap() + 1;
        assert_eq!(doc.path_at(offset).0, "x.e");
        let offset = TEXT.find("3]").unwrap();
        assert_eq!(doc.path_at(offset).0, "x.y.z[2]");
        let offset = TEXT.rfind("q = 5").unwrap();
        let (path, span) = doc.path_at(offset);
        assert_eq!(path, "ant[1].q");
        assert_eq!(doc.snippet(&span), Some("5"));
        let second_header = TEXT.rfind("[[ant]]").unwrap();
        assert_eq!(doc.path_at(second_header).0, "ant[1]");
    }

    #[test]
    fn paths_round_trip() {
        for path in ["a", "a.b", "a[0]", "a.b[2].c", "a[1][2]"] {
            assert_eq!(format_path(&parse_path(path)), path);
        }
    }

    #[test]
    fn line_column_counts_characters() {
        assert_eq!(line_column("ab\ncé d", 7), (2, 4));
        assert_eq!(line_column("ab\ncé d", 5), (2, 2)); // inside 'é': moved back
        assert_eq!(line_column("ab", 99), (1, 3));
        assert_eq!(line_column("", 0), (1, 1));
    }
}
