"""The keys every kind's diagnosis.json shares (docs/diagnosis-json.md), checked on a summary."""

VERDICT_KEYS = {"causes", "cause", "cause_meaning", "confounded", "gain", "held_out_error",
                "candidates", "untestable", "unexplained", "source", "holdout", "criterion"}
CANDIDATE_KEYS = {"cause", "p_value", "gain", "aicc_improvement", "accepted"}
RENAMED = {"name", "aicc_change", "held_out_gain", "why", "message", "untestable_because"}


def assert_shared_keys(summary: dict) -> None:
    """``summary`` holds the shared keys, its candidates and untestable entries theirs, and none
    of the keys they were renamed from."""
    assert VERDICT_KEYS <= set(summary)
    assert set(summary["held_out_error"]) == {"baseline", "extended"}
    for candidate in summary["candidates"]:
        assert CANDIDATE_KEYS <= set(candidate) and not RENAMED & set(candidate)
    for entry in summary["untestable"]:
        assert {"cause", "untestable_reason"} <= set(entry) and not RENAMED & set(entry)
