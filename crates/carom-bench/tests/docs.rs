//! The docs print only figures drawn from the measurements committed beside them: every part
//! marked `<!-- figures: NAME -->` in README.md and docs/, and the accuracy report, is what
//! `carom-bench docs` would draw from the measurements `carom_bench::docs::SOURCES` names.

use std::path::Path;

#[test]
fn every_drawn_figure_in_the_docs_is_what_its_measurements_give() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let stale = carom_bench::docs::update(&root, false).unwrap();
    assert!(
        stale.is_empty(),
        "these docs differ from what their committed measurements draw (run `cargo run \
         --release -p carom-bench -- docs`): {stale:?}"
    );
}

#[test]
fn a_marked_part_is_drawn_again_and_a_broken_one_is_refused() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let sources = carom_bench::docs::Sources::read(&root).unwrap();
    let text = "# A page\n\n<!-- figures: hard-cases/summary -->\nan old figure: 42\n<!-- end figures -->\n\nAfter.\n";
    let drawn = carom_bench::docs::redraw(text, &sources).unwrap();
    assert!(!drawn.contains("42"), "{drawn}");
    assert!(drawn.contains("Box2D v3"), "{drawn}");
    assert!(drawn.starts_with("# A page\n\n<!-- figures: hard-cases/summary -->\n"));
    assert!(
        drawn.ends_with("<!-- end figures -->\n\nAfter.\n"),
        "{drawn}"
    );
    // Drawing twice changes nothing.
    assert_eq!(carom_bench::docs::redraw(&drawn, &sources).unwrap(), drawn);
    let unknown = "<!-- figures: no/such -->\n<!-- end figures -->\n";
    let error = carom_bench::docs::redraw(unknown, &sources).unwrap_err();
    assert!(
        error.contains("line 1") && error.contains("no/such"),
        "{error}"
    );
    let missing = "<!-- figures: table docs/no-such.csv -->\n<!-- end figures -->\n";
    let error = carom_bench::docs::redraw(missing, &sources).unwrap_err();
    assert!(
        error.contains("line 1") && error.contains("no-such.csv"),
        "{error}"
    );
    let unended = "x\n<!-- figures: accuracy/summary -->\nold\n";
    let error = carom_bench::docs::redraw(unended, &sources).unwrap_err();
    assert!(
        error.contains("line 2") && error.contains("end figures"),
        "{error}"
    );
}

#[test]
fn every_measured_table_in_docs_is_drawn_on_a_page() {
    // A table `carom-bench measure` wrote that no page draws is a measurement nobody reads,
    // or a part whose marker was lost.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut pages = String::new();
    for page in carom_bench::docs::marked_files(&root).unwrap() {
        pages.push_str(&std::fs::read_to_string(page).unwrap());
    }
    let mut folders = vec![root.join("docs")];
    let mut tables = 0;
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
                continue;
            }
            let name = path
                .strip_prefix(&root)
                .unwrap()
                .to_string_lossy()
                .into_owned();
            let text = std::fs::read_to_string(&path).unwrap_or_default();
            if name.ends_with(".csv") && text.contains("# command: carom-bench measure ") {
                let marker = format!("<!-- figures: table {name} -->");
                let drawn = carom_bench::docs::SOURCES.contains(&name.as_str());
                assert!(
                    drawn || pages.contains(&marker),
                    "{name}: no page has `{marker}`"
                );
                tables += 1;
            }
        }
    }
    assert!(
        tables > 0,
        "no table under docs/ was written by `carom-bench measure`"
    );
}

#[test]
fn the_effect_table_is_drawn_against_its_first_row() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let sources = carom_bench::docs::Sources::read(&root).unwrap();
    let drawn = sources.draw("effects/cost").unwrap();
    let rows: Vec<&str> = drawn.lines().filter(|l| l.starts_with("| `")).collect();
    assert!(rows.len() >= 2, "{drawn}");
    assert!(
        rows[0].contains("(the baseline)") && rows[0].ends_with("| 1.000 |"),
        "{drawn}"
    );
    // Sleeping removes most of a resting pyramid's work.
    let asleep = rows
        .iter()
        .find(|r| r.starts_with("| `+sleeping`"))
        .unwrap();
    let ratio: f64 = asleep.rsplit('|').nth(1).unwrap().trim().parse().unwrap();
    assert!(ratio < 0.5, "{asleep}");
}

#[test]
fn the_snapshot_table_states_the_largest_ratio_of_its_rows() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let sources = carom_bench::docs::Sources::read(&root).unwrap();
    let drawn = sources.draw("bench/snapshots").unwrap();
    // The ratio column, (snapshot + restore) / step, of every row.
    let ratios: Vec<f64> = drawn
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| scene"))
        .map(|l| l.split('|').nth(7).unwrap().trim().parse().unwrap())
        .collect();
    assert!(!ratios.is_empty(), "{drawn}");
    let most = ratios.iter().copied().fold(0.0, f64::max);
    assert!(
        drawn.contains(&format!("at most {most:.2} of a step")),
        "{drawn}"
    );
}

#[test]
fn the_stage_tables_cover_every_recipe_of_the_speed_table_in_both_engines() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let sources = carom_bench::docs::Sources::read(&root).unwrap();
    let scenes = |name: &str| -> Vec<String> {
        let drawn = sources.draw(name).unwrap();
        drawn
            .lines()
            .filter(|l| l.starts_with("| `"))
            .map(|l| l.split('`').nth(1).unwrap().to_string())
            .collect()
    };
    let recipes = scenes("speed/recipes");
    assert!(!recipes.is_empty());
    for part in ["speed/stages", "speed/work"] {
        let rows = scenes(part);
        for recipe in &recipes {
            // One row of carom's and one of Box2D's, from the same run.
            let count = rows.iter().filter(|s| *s == recipe).count();
            assert_eq!(count, 2, "{part}: {recipe} has {count} rows");
        }
        assert_eq!(rows.len(), 2 * recipes.len(), "{part}: {rows:?}");
    }
}
