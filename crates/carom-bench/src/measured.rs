//! Tables that any measuring program writes, kept with where, when and how they were measured.
//!
//! A program that measures something Rust cannot drive from here (the page in a browser, the
//! npm package under Node, a window under Xvfb, a Bevy app) prints its table as CSV on its
//! standard output: a header line naming the columns as a doc shows them, then one line per
//! row. `carom-bench measure FILE -- COMMAND...` runs it and writes that table to FILE under
//! the same `# measured/machine/cores/command/runs` lines as every other measurement, and a
//! doc draws it with `<!-- figures: table FILE -->` (see [`crate::docs`]).

use crate::sweep::report::Provenance;

/// A measured table: its provenance, the column names and the rows, as text.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Where, when and how it was measured.
    pub provenance: Provenance,
    /// The column names.
    pub header: Vec<String>,
    /// The rows, each as long as the header.
    pub rows: Vec<Vec<String>>,
}

/// The fields of one CSV line: split at commas outside double quotes; a quoted field loses
/// its quotes and `""` inside it is one `"`. An error for a quote left open.
pub fn fields(line: &str) -> Result<Vec<String>, String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', false) if field.is_empty() => quoted = true,
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            ('"', true) => quoted = false,
            (',', false) => fields.push(std::mem::take(&mut field)),
            (c, _) => field.push(c),
        }
    }
    if quoted {
        return Err(format!("`{line}` leaves a quote open"));
    }
    fields.push(field);
    Ok(fields)
}

/// Checks a command's output `csv` as a table: a header of at least two columns, at least one
/// row, every row as long as the header. Returns the header and the rows.
pub fn check(csv: &str) -> Result<(Vec<String>, Vec<Vec<String>>), String> {
    let mut lines = csv.lines().filter(|line| !line.trim().is_empty());
    let header = fields(lines.next().ok_or("no header line")?)?;
    if header.len() < 2 {
        return Err(format!(
            "its header `{}` has not two columns",
            header.join(",")
        ));
    }
    let rows = lines
        .map(|line| {
            let row = fields(line)?;
            if row.len() == header.len() {
                Ok(row)
            } else {
                Err(format!(
                    "`{line}` has {} fields where the header has {}",
                    row.len(),
                    header.len()
                ))
            }
        })
        .collect::<Result<Vec<_>, String>>()?;
    if rows.is_empty() {
        return Err("no rows".into());
    }
    Ok((header, rows))
}

/// Reads a table written by [`write()`].
pub fn parse(text: &str) -> Result<Table, String> {
    let provenance = Provenance::parse(text).ok_or("no `# measured: ...` lines at its top")?;
    let body: String = text
        .lines()
        .filter(|line| !line.starts_with('#'))
        .map(|line| format!("{line}\n"))
        .collect();
    let (header, rows) = check(&body)?;
    Ok(Table {
        provenance,
        header,
        rows,
    })
}

/// The file [`parse`] reads: `provenance`'s lines, then the command's `csv`, after checking it.
pub fn write(provenance: &Provenance, csv: &str) -> Result<String, String> {
    check(csv)?;
    let mut text = provenance.header();
    for line in csv.lines().filter(|line| !line.trim().is_empty()) {
        text.push_str(line);
        text.push('\n');
    }
    Ok(text)
}

impl Table {
    /// The table in markdown, under a line naming when, where and by what it was measured.
    pub fn markdown(&self) -> String {
        let cell = |text: &str| text.replace('|', "\\|");
        let line = |cells: &[String]| {
            let cells: Vec<String> = cells.iter().map(|c| cell(c)).collect();
            format!("| {} |\n", cells.join(" | "))
        };
        let machine = &self.provenance.machine;
        let mut out = format!(
            "Measured {} on {} ({} cores) by `{}`:\n\n",
            machine.date, machine.cpu, machine.cores, self.provenance.command
        );
        out.push_str(&line(&self.header));
        out.push_str(&format!("|{}\n", "---|".repeat(self.header.len())));
        for row in &self.rows {
            out.push_str(&line(row));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::report::Machine;

    fn provenance() -> Provenance {
        Provenance {
            machine: Machine {
                cpu: "a CPU".into(),
                cores: 2,
                date: "2026-12-03".into(),
            },
            command: "carom-bench measure out.csv -- ./measure".into(),
            runs: 3,
        }
    }

    #[test]
    fn quoted_fields_keep_their_commas_and_quotes() {
        assert_eq!(
            fields(r#"a,"b, c","say ""hi""",,"#).unwrap(),
            ["a", "b, c", "say \"hi\"", "", ""]
        );
        assert!(fields(r#"a,"b"#).is_err());
    }

    #[test]
    fn a_written_table_reads_back_and_draws() {
        let csv = "scene,frames/s,ratio\npyramid,16.3,\"1.2x, 1.3x\"\nlarge | pyramid,2.5,1x\n";
        let text = write(&provenance(), csv).unwrap();
        let table = parse(&text).unwrap();
        assert_eq!(table.provenance, provenance());
        assert_eq!(table.header, ["scene", "frames/s", "ratio"]);
        assert_eq!(table.rows[0], ["pyramid", "16.3", "1.2x, 1.3x"]);
        let drawn = table.markdown();
        assert!(drawn.starts_with(
            "Measured 2026-12-03 on a CPU (2 cores) by `carom-bench measure out.csv -- ./measure`"
        ));
        assert!(drawn.contains("| scene | frames/s | ratio |\n|---|---|---|\n"));
        assert!(drawn.contains("| large \\| pyramid | 2.5 | 1x |\n"));
    }

    #[test]
    fn a_command_that_printed_no_table_is_refused() {
        for (csv, why) in [
            ("", "no header"),
            ("one\nrow\n", "has not two columns"),
            ("a,b\n", "no rows"),
            ("a,b\n1,2,3\n", "has 3 fields where the header has 2"),
        ] {
            let error = write(&provenance(), csv).unwrap_err();
            assert!(error.contains(why), "{csv:?}: {error}");
        }
    }
}
