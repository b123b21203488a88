//! The HTML report of a run in a real headless browser (Chromium through
//! `chromedriver`, as the console's browser tests): a run of the tester against a
//! component that takes commands from anyone is rendered, with hostile markup planted in
//! the texts that come from the network. The page shows one row per check and the
//! counts in its contents list; the filter shows only the required failures, then only
//! the checks that did not pass; a check's messages open; no planted markup became an
//! element or ran.
//!
//! Without `chromedriver` the test is skipped with a message, unless
//! `JAUS_REQUIRE_BROWSER` is set.

mod broken;
#[path = "../../ocu/tests/common/chromium.rs"]
mod chromium;

use std::time::{Duration, Instant};

use chromium::{js, wait_for, Browser};
use fantoccini::Locator;
use jaus::net::{Node, NodeConfig};
use jaus::Address;
use jaus_conform::memory::{MemorySession, TESTER};
use jaus_conform::session::Voices;
use jaus_conform::{report, Options, Verdict};
use jaus_node::host::{Host, Stock};

/// Markup a hostile component could send as its identification or in a field.
const EVIL: &str =
    "<img src=x onerror=\"document.title='pwned'\"><script>document.title='pwned'</script>";

#[tokio::test(flavor = "current_thread")]
async fn the_html_report_renders_filters_and_stays_inert() {
    // A Global Vector Driver that obeys anyone, and a sound Global Pose Sensor.
    let t0 = Instant::now();
    let mut host = Host::new(1, 1, t0);
    let mut node = Node::new(
        NodeConfig {
            peers: vec![TESTER],
            ..NodeConfig::default()
        },
        t0,
    );
    let gvd = host.build(&Host::entry(Stock::by_id(34).unwrap())).unwrap();
    node.add_boxed(Box::new(broken::AnyoneCommands::new(gvd)))
        .unwrap();
    let gpos = host.build(&Host::entry(Stock::by_id(38).unwrap())).unwrap();
    node.add_boxed(gpos).unwrap();
    let voices = Voices::on(200, 1);
    let mut session = MemorySession::new(node, &voices, t0).unwrap();
    let spec = jaus_spec::load_sdk().unwrap();
    let targets = [Address::new(1, 1, 34, 1), Address::new(1, 1, 38, 1)];
    let mut run = jaus_conform::run(&mut session, &spec, voices, &targets, Options::default());
    assert!(!run.passed());
    // What the network could have said, planted where the page prints it.
    run.peer = EVIL.into();
    run.components[0].identification = Some(EVIL.into());
    run.components[1].outcomes[0].detail = EVIL.into();
    run.components[1].outcomes[0].evidence[0].message = EVIL.into();

    let checks = run.checks();
    let required: usize = run.components.iter().map(|c| c.required_failures()).sum();
    let not_passed: usize = run
        .components
        .iter()
        .map(|c| c.outcomes.len() - c.count(Verdict::Pass))
        .sum();
    assert!(required > 0 && not_passed > required && checks > not_passed);

    let dir = std::env::temp_dir().join(format!("jaus-conform-html-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let page = dir.join("run.html");
    std::fs::write(&page, report::html(&run)).unwrap();

    let Some(browser) = Browser::start().await else {
        return;
    };
    let c = &browser.client;
    c.goto(&format!("file://{}", page.display())).await.unwrap();
    let visible = "return [...document.querySelectorAll('tr.check')].filter(r => r.offsetParent !== null).length";
    let rows = wait_for("the report's rows", Duration::from_secs(10), async || {
        js(c, "return document.querySelectorAll('tr.check').length")
            .await
            .as_u64()
            .filter(|n| *n > 0)
    })
    .await;
    assert_eq!(rows as usize, checks);
    assert_eq!(js(c, visible).await.as_u64(), Some(checks as u64));
    // The contents list gives each component's counts.
    let contents = c
        .find(Locator::Id("contents"))
        .await
        .unwrap()
        .text()
        .await
        .unwrap();
    for comp in &run.components {
        let line = format!(
            "{} checks, {} fail ({} required)",
            comp.outcomes.len(),
            comp.count(Verdict::Fail),
            comp.required_failures()
        );
        assert!(contents.contains(&line), "{contents}");
    }
    // The filter: required failures only, then every check that did not pass.
    c.find(Locator::Css("#filter input[value='only-required']"))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
    assert_eq!(js(c, visible).await.as_u64(), Some(required as u64));
    c.find(Locator::Css("#filter input[value='only-failed']"))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
    assert_eq!(js(c, visible).await.as_u64(), Some(not_passed as u64));
    // A failed check's messages open.
    let first_failed = c
        .find(Locator::Css("tr.required-failure summary"))
        .await
        .unwrap();
    first_failed.click().await.unwrap();
    let shown = js(
        c,
        "const d = document.querySelector('tr.required-failure details'); return d.open && d.querySelector('pre').offsetHeight > 0",
    )
    .await;
    assert_eq!(shown.as_bool(), Some(true));
    // Nothing planted became an element or ran; the text shows as text.
    tokio::time::sleep(Duration::from_millis(300)).await;
    assert_eq!(
        js(c, "return document.querySelectorAll('img').length")
            .await
            .as_u64(),
        Some(0)
    );
    assert_eq!(
        js(c, "return document.querySelectorAll('script').length")
            .await
            .as_u64(),
        Some(1)
    );
    // The title still reads as written: the planted text, not what its script would
    // have set.
    let title = js(c, "return document.title").await;
    assert_eq!(
        title.as_str(),
        Some(format!("{}: {EVIL}", run.tool).as_str())
    );
    let body = c
        .find(Locator::Css("body"))
        .await
        .unwrap()
        .text()
        .await
        .unwrap();
    assert!(
        body.contains("<img src=x"),
        "the planted text is shown as text"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
