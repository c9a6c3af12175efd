//! The report page: sections of text, figures (inline SVG) and tables, written as one
//! self-contained HTML file (no network, no external file). A small inline script
//! records on `<body>` how many figures there are and how many the browser laid out with
//! a drawing in them (`data-figures`, `data-figures-rendered`), so a headless browser
//! can check the page.

use std::fmt::Write;

/// One figure: an SVG drawing and its caption.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub caption: String,
    pub svg: String,
}

/// A table cell: text and an optional CSS class: a verdict's, or `n` for short text kept
/// on one line (numbers, units).
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    pub text: String,
    pub class: Option<&'static str>,
}

impl From<String> for Cell {
    fn from(text: String) -> Self {
        Cell { text, class: None }
    }
}

impl From<&str> for Cell {
    fn from(text: &str) -> Self {
        Cell::from(text.to_string())
    }
}

/// A table with a header row.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<Cell>>,
}

/// A part of the page: heading, paragraphs, figures, tables, in that order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Section {
    pub heading: String,
    pub paragraphs: Vec<String>,
    pub figures: Vec<Figure>,
    pub tables: Vec<Table>,
}

/// The whole page.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Page {
    pub title: String,
    pub sections: Vec<Section>,
}

const STYLE: &str = "body{font-family:sans-serif;max-width:980px;margin:2em auto;color:#222}\
h1{font-size:1.6em}h2{font-size:1.25em;border-bottom:1px solid #ccc;padding-bottom:.2em}\
figure{margin:1.2em 0}figcaption{font-size:.9em;color:#555}\
table{border-collapse:collapse;font-size:.85em;margin:1em 0;width:100%}\
td,th{border:1px solid #ccc;padding:.25em .5em;text-align:left;vertical-align:top;\
overflow-wrap:break-word}.n,.reproduced,.deviates,.explained{white-space:nowrap}\
td:last-child{width:30%;overflow-wrap:anywhere}\
th{background:#f3f3f3}.reproduced{background:#e3f4e3}.deviates{background:#fbe3e3}\
.explained{background:#fff4d6}";

const SCRIPT: &str = "window.addEventListener('load',function(){\
var s=document.querySelectorAll('figure svg'),n=0;\
s.forEach(function(e){var b=e.getBoundingClientRect();\
if(b.width>0&&b.height>0&&e.querySelector('polyline,path,polygon'))n++;});\
document.body.setAttribute('data-figures',s.length);\
document.body.setAttribute('data-figures-rendered',n);\
console.log('skyforge-report: '+n+' of '+s.length+' figures rendered');});";

impl Page {
    /// Number of figures on the page.
    pub fn figures(&self) -> usize {
        self.sections.iter().map(|s| s.figures.len()).sum()
    }

    /// The page as HTML text.
    pub fn to_html(&self) -> String {
        let mut h = String::new();
        let title = escape(&self.title);
        let _ = write!(
            h,
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
             <title>{title}</title><style>{STYLE}</style><script>{SCRIPT}</script></head>\
             <body>\n<h1>{title}</h1>\n"
        );
        for (k, s) in self.sections.iter().enumerate() {
            let _ = writeln!(h, "<section id=\"s{k}\"><h2>{}</h2>", escape(&s.heading));
            for p in &s.paragraphs {
                let _ = writeln!(h, "<p>{}</p>", escape(p));
            }
            for f in &s.figures {
                let _ = writeln!(
                    h,
                    "<figure>{}<figcaption>{}</figcaption></figure>",
                    f.svg,
                    escape(&f.caption)
                );
            }
            for t in &s.tables {
                table_html(&mut h, t);
            }
            h.push_str("</section>\n");
        }
        h.push_str("</body></html>\n");
        h
    }
}

fn table_html(h: &mut String, t: &Table) {
    h.push_str("<table><tr>");
    for c in &t.header {
        let _ = write!(h, "<th>{}</th>", escape(c));
    }
    h.push_str("</tr>\n");
    for row in &t.rows {
        h.push_str("<tr>");
        for c in row {
            match c.class {
                Some(class) => {
                    let _ = write!(h, "<td class=\"{class}\">{}</td>", escape(&c.text));
                }
                None => {
                    let _ = write!(h, "<td>{}</td>", escape(&c.text));
                }
            }
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
}

/// `text` with the HTML special characters escaped.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for ch in text.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_from_the_data_is_escaped_and_svg_is_inlined() {
        let page = Page {
            title: "run <a> & b".into(),
            sections: vec![Section {
                heading: "h\"1".into(),
                paragraphs: vec!["<script>alert(1)</script>".into()],
                figures: vec![Figure {
                    caption: "c<".into(),
                    svg: "<svg><polyline/></svg>".into(),
                }],
                tables: vec![Table {
                    header: vec!["verdict".into()],
                    rows: vec![vec![Cell {
                        text: "reproduced".into(),
                        class: Some("reproduced"),
                    }]],
                }],
            }],
        };
        let html = page.to_html();
        assert!(html.contains("<title>run &lt;a&gt; &amp; b</title>"));
        assert!(html.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
        assert!(!html.contains("<script>alert"));
        assert!(html.contains("<figure><svg><polyline/></svg><figcaption>c&lt;"));
        assert!(html.contains("<td class=\"reproduced\">reproduced</td>"));
        assert_eq!(page.figures(), 1);
        assert!(!html.contains("http"), "no external resource");
    }
}
