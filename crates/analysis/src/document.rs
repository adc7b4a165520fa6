//! A report as a document: headings, paragraphs, tables, lists and figures, written as Markdown
//! (`report.md`) and as HTML (`report.html`) from the same blocks, so that both carry the same
//! tables and the same words.
//!
//! Text is kept as plain strings with code spans apart ([`Inline`]), never as pre-formatted
//! markup: each writer escapes what it must (HTML escapes everything that came from input — scene
//! names, technique specs, reasons), so nothing in a name can break out of its cell.

use std::fmt::Write as _;

/// A run of text: plain, or code (Markdown's backticks, HTML's `<code>`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Inline {
    /// Plain text.
    Text(String),
    /// Code: a name, a formula, a path.
    Code(String),
}

/// Plain text.
pub(crate) fn text(s: impl Into<String>) -> Inline {
    Inline::Text(s.into())
}

/// A code span.
pub(crate) fn code(s: impl Into<String>) -> Inline {
    Inline::Code(s.into())
}

/// How a column's cells are aligned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Align {
    /// Text.
    Left,
    /// Numbers.
    Right,
}

/// A table: a header row and rows of cells of plain text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Table {
    /// The column names.
    pub(crate) header: Vec<String>,
    /// Each column's alignment.
    pub(crate) align: Vec<Align>,
    /// The rows, each as long as the header.
    pub(crate) rows: Vec<Vec<String>>,
}

/// One block of a document.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Block {
    /// A heading of level 1 to 3.
    Heading(u8, Vec<Inline>),
    /// A paragraph of one or more lines (soft line breaks between them).
    Paragraph(Vec<Vec<Inline>>),
    /// A table.
    Table(Table),
    /// A bulleted list.
    List(Vec<Vec<Inline>>),
    /// A figure file beside the report, with its alternative text.
    Figure {
        /// What it shows.
        alt: String,
        /// Its path, relative to the report.
        src: String,
    },
}

/// A paragraph of one line.
pub(crate) fn paragraph(line: Vec<Inline>) -> Block {
    Block::Paragraph(vec![line])
}

fn inline_markdown(out: &mut String, line: &[Inline]) {
    for part in line {
        match part {
            Inline::Text(t) => out.push_str(t),
            Inline::Code(c) => {
                out.push('`');
                out.push_str(c);
                out.push('`');
            }
        }
    }
}

/// The blocks as Markdown: each block's lines, blocks separated by one empty line.
pub(crate) fn markdown(blocks: &[Block]) -> String {
    let rendered: Vec<String> = blocks
        .iter()
        .map(|block| {
            let mut md = String::new();
            match block {
                Block::Heading(level, line) => {
                    md.push_str(&"#".repeat(usize::from(*level)));
                    md.push(' ');
                    inline_markdown(&mut md, line);
                    md.push('\n');
                }
                Block::Paragraph(lines) => {
                    for line in lines {
                        inline_markdown(&mut md, line);
                        md.push('\n');
                    }
                }
                Block::List(items) => {
                    for item in items {
                        md.push_str("- ");
                        inline_markdown(&mut md, item);
                        md.push('\n');
                    }
                }
                Block::Figure { alt, src } => {
                    writeln!(md, "![{alt}]({src})").expect("writing to a string");
                }
                Block::Table(table) => {
                    writeln!(md, "| {} |", table.header.join(" | ")).expect("writing to a string");
                    md.push('|');
                    for align in &table.align {
                        md.push_str(match align {
                            Align::Left => "---|",
                            Align::Right => "---:|",
                        });
                    }
                    md.push('\n');
                    for row in &table.rows {
                        writeln!(md, "| {} |", row.join(" | ")).expect("writing to a string");
                    }
                }
            }
            md
        })
        .collect();
    rendered.join("\n")
}

/// `text` safe as HTML text and as a quoted attribute value.
pub(crate) fn escape_html(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
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

/// A line of inline text as HTML, escaped.
pub(crate) fn inline_html(line: &[Inline]) -> String {
    let mut out = String::new();
    for part in line {
        match part {
            Inline::Text(t) => out.push_str(&escape_html(t)),
            Inline::Code(c) => {
                write!(out, "<code>{}</code>", escape_html(c)).expect("writing to a string")
            }
        }
    }
    out
}

/// A table as HTML whose headers sort its rows when clicked (the page's script does it).
pub(crate) fn table_html(table: &Table) -> String {
    let mut html = String::from("<div class=\"table\"><table class=\"sortable\">\n<thead><tr>");
    for (name, align) in table.header.iter().zip(&table.align) {
        let class = match align {
            Align::Left => "",
            Align::Right => " class=\"num\"",
        };
        write!(
            html,
            "<th{class} scope=\"col\" tabindex=\"0\" title=\"sort by this column\">{}</th>",
            escape_html(name)
        )
        .expect("writing to a string");
    }
    html.push_str("</tr></thead>\n<tbody>\n");
    for row in &table.rows {
        html.push_str("<tr>");
        for (cell, align) in row.iter().zip(&table.align) {
            let class = match align {
                Align::Left => "",
                Align::Right => " class=\"num\"",
            };
            write!(html, "<td{class}>{}</td>", escape_html(cell)).expect("writing to a string");
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</tbody></table></div>\n");
    html
}

/// The blocks as HTML; `figure(src, alt)` gives the markup of a figure (the page inlines its
/// SVG).
pub(crate) fn html(blocks: &[Block], figure: &dyn Fn(&str, &str) -> String) -> String {
    let mut out = String::new();
    for block in blocks {
        match block {
            Block::Heading(level, line) => {
                writeln!(out, "<h{level}>{}</h{level}>", inline_html(line))
                    .expect("writing to a string");
            }
            Block::Paragraph(lines) => {
                let lines: Vec<String> = lines.iter().map(|l| inline_html(l)).collect();
                writeln!(out, "<p>{}</p>", lines.join("\n")).expect("writing to a string");
            }
            Block::List(items) => {
                out.push_str("<ul>\n");
                for item in items {
                    writeln!(out, "<li>{}</li>", inline_html(item)).expect("writing to a string");
                }
                out.push_str("</ul>\n");
            }
            Block::Figure { alt, src } => out.push_str(&figure(src, alt)),
            Block::Table(table) => out.push_str(&table_html(table)),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blocks() -> Vec<Block> {
        vec![
            Block::Heading(1, vec![text("Title: "), code("a<b")]),
            Block::Paragraph(vec![vec![text("one & two")], vec![text("three")]]),
            Block::Table(Table {
                header: vec!["name".into(), "n".into()],
                align: vec![Align::Left, Align::Right],
                rows: vec![vec!["<x>".into(), "1".into()]],
            }),
            Block::List(vec![vec![text("item")]]),
            Block::Figure {
                alt: "plot".into(),
                src: "p.png".into(),
            },
        ]
    }

    #[test]
    fn markdown_separates_blocks_by_one_empty_line() {
        assert_eq!(
            markdown(&blocks()),
            "# Title: `a<b`\n\none & two\nthree\n\n| name | n |\n|---|---:|\n| <x> | 1 |\n\n\
             - item\n\n![plot](p.png)\n"
        );
    }

    #[test]
    fn html_escapes_every_text() {
        let html = html(&blocks(), &|src, alt| format!("[{src}|{alt}]"));
        assert!(
            html.contains("<h1>Title: <code>a&lt;b</code></h1>"),
            "{html}"
        );
        assert!(html.contains("<p>one &amp; two\nthree</p>"), "{html}");
        assert!(
            html.contains("<td>&lt;x&gt;</td><td class=\"num\">1</td>"),
            "{html}"
        );
        assert!(html.contains("[p.png|plot]"), "{html}");
        assert!(!html.contains("<x>"), "{html}");
        assert_eq!(
            escape_html("'\"<&>"),
            "&#39;&quot;&lt;&amp;&gt;",
            "every special character"
        );
    }
}
