//! One force channel's gain off, through the binary (forty-eighth session). The pair is family a
//! dataset 71 of the concealed benchmark at seed 27272 (`fixtures/README.md`): a null (Ti6Al4V, 8
//! conditions, two rakes) whose recorded feed force was then multiplied by 0.8818228 (a feed
//! channel reading 11.8 % low, the cutting force untouched). Before the per-channel gains joined
//! the instrument competitors it was named `force_crosstalk`. The report must claim nothing, name
//! the feed channel's gain, ask for the dead-weight check and give the gain it fitted.

use super::json as report;

/// The factor applied to the feed-force column of the null (fixtures/README.md).
const APPLIED: f64 = 0.881_822_786;

#[test]
fn a_gain_on_the_feed_channel_alone_is_no_physics() {
    let r = report(&[
        "diagnose",
        "--recordings",
        "fixtures/diagnose/channel_gain_recordings.csv",
        "--simulation",
        "fixtures/diagnose/channel_gain_simulation.csv",
        "--json",
    ]);
    assert!(r["selected"].as_array().unwrap().is_empty(), "{r}");
    let explanation = r["explanation"].as_str().unwrap();
    assert!(
        explanation.contains("a gain error of the feed-force channel alone explains the mismatch"),
        "{explanation}"
    );
    assert!(explanation.contains("check the instrument before trusting"), "{explanation}");
    assert!(!explanation.contains("treat the model as biased"), "{explanation}");
    let next = r["next_test"].as_str().unwrap();
    assert!(next.contains("dead weights") && next.contains("feed-force channel"), "{next}");
    // The stopped candidate's reason gives the fitted factor: within 3 % of the one applied (the
    // feed force's noise is 3.2 % per test over 8 tests, 1.1 % on the mean; the prior of sd
    // ln(1.2) / 2 pulls it towards 1 by about 2 % of the log).
    let reason = r["mechanisms"]
        .as_array()
        .unwrap()
        .iter()
        .find_map(|m| m["reason"].as_str().filter(|s| s.contains("feed-force channel alone")))
        .expect("a candidate stopped by the feed channel's gain");
    let factor: f64 = reason[reason.find("fitted factor ").unwrap() + 14..]
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .next()
        .and_then(|w| w.parse().ok())
        .expect("a factor");
    assert!((factor / APPLIED - 1.0).abs() < 0.03, "{factor} against {APPLIED}");
}

/// Family a dataset 86 of seed 27272, a null of 6 conditions, with the feed force x 0.8750910
/// (fixtures/README.md): the global misfit is not significant, so the verdict is `none`; the text
/// and the next test must still send the user to the instrument, not say that nothing is needed.
#[test]
fn a_quiet_verdict_still_asks_for_the_channel_check() {
    let r = report(&[
        "diagnose",
        "--recordings",
        "fixtures/diagnose/channel_gain_quiet_recordings.csv",
        "--simulation",
        "fixtures/diagnose/channel_gain_quiet_simulation.csv",
        "--json",
    ]);
    assert_eq!(r["verdict"], "none", "{r}");
    let explanation = r["explanation"].as_str().unwrap();
    assert!(
        explanation.contains("No physics is needed: a gain error of the feed-force channel alone"),
        "{explanation}"
    );
    assert!(!explanation.contains("would only fit noise"), "{explanation}");
    let next = r["next_test"].as_str().unwrap();
    assert!(next.starts_with("check the force channels with dead weights"), "{next}");
}

/// Family b dataset 95 of the concealed benchmark at seed 28282 (fixtures/README.md): a
/// one-channel gain decoy, the feed force x 0.8548 (AISI 1045, 25 conditions, Merchant's closure).
/// A cross-talk into the feed channel draws it almost as well, since Ft/Fc changes little here
/// (0.26-0.37). The gain, an instrument explanation like the cross-talk, competes with it without
/// its prior, so the report claims neither and asks for the dead-weight check.
#[test]
fn a_channel_gain_and_a_cross_talk_compete_on_equal_terms() {
    let r = report(&[
        "diagnose",
        "--recordings",
        "fixtures/diagnose/channel_gain_vs_crosstalk_recordings.csv",
        "--simulation",
        "fixtures/diagnose/channel_gain_vs_crosstalk_simulation.csv",
        "--json",
    ]);
    assert!(r["selected"].as_array().unwrap().is_empty(), "{r}");
    let crosstalk = r["mechanisms"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["id"] == "force_crosstalk" && m["reason"].as_str().unwrap().contains("feed-force channel alone"))
        .expect("the cross-talk stopped by the feed channel's gain");
    let reason = crosstalk["reason"].as_str().unwrap();
    let factor: f64 = reason[reason.find("fitted factor ").unwrap() + 14..]
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .next()
        .and_then(|w| w.parse().ok())
        .expect("a factor");
    // The generator's factor (truth-b.json, strength 0.8548139), within 3 %.
    assert!((factor / 0.854_813_9 - 1.0).abs() < 0.03, "{factor}");
    assert!(r["next_test"].as_str().unwrap().starts_with("check the force channels with dead weights"), "{r}");
}
