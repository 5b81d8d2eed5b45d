//! `snapshot --junit FILE`: the run as JUnit XML, the report CI services read (a test per
//! figure, with its time, and the numbers of a failure).

use std::fmt::Write as _;

/// How one figure's check ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// It matched (or was blessed).
    Passed,
    /// It differed: the one-line message and the details (numbers, the diff image's path).
    Failed { message: String, details: String },
    /// It could not be checked: the lesson does not validate, or the figure cannot be made.
    Error { message: String, details: String },
}

/// One `<testcase>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// The lesson (its file stem): the test's class.
    pub class: String,
    /// The figure.
    pub name: String,
    /// Seconds the figure took to make and compare.
    pub seconds: f64,
    /// How it ended.
    pub outcome: Outcome,
}

/// Text for XML: escaped as HTML is (`&`, `<`, `>`, `"`, `'`), after dropping the
/// characters XML 1.0 cannot hold (control characters other than tab and newlines).
fn xml(s: &str) -> String {
    let allowed: String =
        s.chars().filter(|&c| matches!(c, '\t' | '\n' | '\r') || !((c as u32) < 0x20 || c == '\u{fffe}' || c == '\u{ffff}')).collect();
    crate::site::html::escape(&allowed)
}

/// The cases as one JUnit XML document: a `<testsuites>` holding one `<testsuite>` named
/// `suite`, the counts on both (the attributes the Ant/Jenkins schema has and GitHub,
/// GitLab and Azure read).
pub fn document(suite: &str, cases: &[Case], timestamp: &str) -> String {
    let failures = cases.iter().filter(|c| matches!(c.outcome, Outcome::Failed { .. })).count();
    let errors = cases.iter().filter(|c| matches!(c.outcome, Outcome::Error { .. })).count();
    let time: f64 = cases.iter().map(|c| c.seconds).sum();
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let counts = format!("tests=\"{}\" failures=\"{failures}\" errors=\"{errors}\" time=\"{time:.3}\"", cases.len());
    let _ = writeln!(s, "<testsuites name=\"{}\" {counts}>", xml(suite));
    let _ = writeln!(s, "  <testsuite name=\"{}\" {counts} skipped=\"0\" timestamp=\"{}\">", xml(suite), xml(timestamp));
    for c in cases {
        let head = format!("    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3}\"", xml(&c.class), xml(&c.name), c.seconds);
        match &c.outcome {
            Outcome::Passed => {
                let _ = writeln!(s, "{head}/>");
            }
            Outcome::Failed { message, details } | Outcome::Error { message, details } => {
                let tag = if matches!(c.outcome, Outcome::Failed { .. }) { "failure" } else { "error" };
                // The failure's type is the command: `snapshot`, `grade`.
                let kind = if tag == "failure" { suite.rsplit(' ').next().unwrap_or(suite) } else { "input" };
                let _ = writeln!(s, "{head}>");
                let _ = writeln!(s, "      <{tag} message=\"{}\" type=\"{kind}\">{}</{tag}>", xml(message), xml(details));
                let _ = writeln!(s, "    </testcase>");
            }
        }
    }
    s.push_str("  </testsuite>\n</testsuites>\n");
    s
}

/// Now as an ISO 8601 UTC time (the suite's `timestamp`), from the system clock.
pub fn now() -> String {
    let secs = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (Hinnant, "chrono-Compatible Low-Level Date Algorithms").
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}", rem / 3600, rem % 3600 / 60, rem % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_document_counts_and_escapes_what_it_holds() {
        let cases = [
            Case { class: "04-shininess".into(), name: "sweep".into(), seconds: 0.25, outcome: Outcome::Passed },
            Case {
                class: "04-shininess".into(),
                name: "ks<n>".into(),
                seconds: 0.5,
                outcome: Outcome::Failed { message: "2.3% of pixels differ".into(), details: "diff: a&b.png\u{1}".into() },
            },
            Case {
                class: "bad".into(),
                name: "(lesson)".into(),
                seconds: 0.0,
                outcome: Outcome::Error { message: "bad.toml:3:7: \"x\"".into(), details: "hint".into() },
            },
        ];
        let d = document("shadelab snapshot", &cases, "2026-12-05T10:00:00");
        assert!(d.contains("<testsuites name=\"shadelab snapshot\" tests=\"3\" failures=\"1\" errors=\"1\" time=\"0.750\">"), "{d}");
        assert!(d.contains("<testcase classname=\"04-shininess\" name=\"sweep\" time=\"0.250\"/>"), "{d}");
        assert!(d.contains("name=\"ks&lt;n&gt;\"") && d.contains("diff: a&amp;b.png</failure>"), "{d}");
        assert!(d.contains("<error message=\"bad.toml:3:7: &quot;x&quot;\" type=\"input\">hint</error>"), "{d}");
        assert_eq!(d.matches("<testcase").count(), 3);
        assert!(!d.contains('\u{1}'), "no control characters");
    }

    #[test]
    fn the_timestamp_is_a_civil_date() {
        let t = now();
        assert_eq!(t.len(), 19, "{t}");
        assert!(t.starts_with("20") && &t[10..11] == "T", "{t}");
    }
}
