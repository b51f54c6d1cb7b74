"""The generated prose of paper 000's notebook: the findings table at the top, one claim's details, the conclusions.

Every number and every interpretive word comes from the claims' rules and the exploration's records.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

from ...verdicts import as_estimate

__all__ = ["summary", "findings_table", "claim_details", "conclusions", "reproduced_where", "condition_rows"]


def _one(m: Any) -> str:
    e = as_estimate(m)
    if e.ci_low == e.ci_high:
        return f"{e.value:.3g}"
    return f"{e.value:.3g} [{e.ci_low:.3g}, {e.ci_high:.3g}]"


def summary(measured: Any, limit: int = 3) -> str:
    """A measured value in a few words: an estimate with its interval; a list by its ends; parts by name (the first
    ``limit``, then the range of the rest)."""
    if measured is None:
        return "-"
    if isinstance(measured, (list, tuple)):
        return f"{_one(measured[0])} ... {_one(measured[-1])} ({len(measured)} points)"
    if isinstance(measured, dict) and "value" not in measured:
        items = list(measured.items())
        text = "; ".join(f"{k}: {summary(v)}" for k, v in items[:limit])
        rest = [as_estimate(v).value for _, v in items[limit:] if not isinstance(v, (list, tuple))]
        if rest:
            text += f"; {len(rest)} more in {min(rest):.3g}-{max(rest):.3g}"
        return text
    return _one(measured)


def findings_table(claims) -> str:
    """One line per claim: what the paper said, what was measured (pooled replicates), verdict and label."""
    rows = ["| claim | paper | measured (default register, pooled replicates) | verdict | label |",
            "|---|---|---|---|---|"]
    for c in sorted(claims, key=lambda c: int(c.id.split("-")[1])):
        label = c.robustness["label"] if c.robustness else "-"
        rows.append(f"| **{c.id}** {c.statement} | {c.paper_value} | {summary(c.measured)} | {c.verdict} | {label} |")
    return "\n".join(rows)


def claim_details(results, ex, claim_id: str) -> str:
    """The claim's rule, its verdict and label per part, the coverage and where a condition changes a part."""
    c = next(c for c in results.claims if c.id == claim_id)
    rec = c.robustness
    lines = [f"**{c.id}** ({c.statement}) **Rule:** {c.acceptance}.", "",
             f"**Verdict: {c.verdict}; label: {rec['coverage']}.**", "",
             "| part | verdict | label | replicates |", "|---|---|---|---|"]
    for name, p in rec["parts"].items():
        lines.append(f"| {name} | {p['verdict']} | {p['label']} | {', '.join(p['replicate_verdicts'])} |")
    if rec["where"]:
        lines += ["", "Where a verdict differs: " + "; ".join(rec["where"]) + "."]
    return "\n".join(lines)


def conclusions(claims, ex) -> str:
    """The closing section: the verdicts and labels counted, each claim in one line, and what the register tried."""
    checkable = [c for c in claims if c.verdict != "not checkable"]
    verdicts = Counter(c.verdict for c in checkable)
    labels = Counter(c.robustness["label"] for c in checkable if c.robustness)
    adversarial = [e.name for e in ex.register if e.origin == "adversarial"]
    lines = [f"Of {len(checkable)} checkable claims: " + ", ".join(f"{n} {v}" for v, n in verdicts.most_common())
             + "; labels " + ", ".join(f"{n} {lab}" for lab, n in labels.most_common()) + ".",
             f"The exploration ran {ex.settings['replicates']} independent replicates, "
             f"{sum(r.stage == 'single' for r in ex.runs)} one-at-a-time and {sum(r.stage == 'joint' for r in ex.runs)} "
             f"joint configurations over {len(ex.register)} register entries"
             + (f" (added while trying to flip a label: {', '.join(adversarial)})." if adversarial else "."), ""]
    for c in sorted(claims, key=lambda c: int(c.id.split("-")[1])):
        where = f"; differs: {'; '.join(c.robustness['where'][:3])}" if c.robustness and c.robustness["where"] else ""
        label = f", {c.robustness['label']}" if c.robustness else ""
        lines.append(f"- **{c.id}** {c.verdict}{label}{where}.")
    return "\n".join(lines)


def reproduced_where(rule, named: dict) -> list:
    """The names whose measured value the rule judges ``reproduced``: ``named`` maps a name (a condition, or a part
    of an :class:`~tvtrack.verdicts.AllOf` rule when ``rule`` is one) to what the rule (or that part's rule) reads."""
    parts = getattr(rule, "parts", None)
    return [k for k, m in named.items() if (parts[k] if parts else rule).decide(m) == "reproduced"]


def condition_rows(ex, claim_id: str) -> list:
    """``(description, measured)`` of the claim pooled at the default, then under each condition of its exploration."""
    rows = [("default (pooled replicates)", ex.measured(claim_id))]
    for c in ex.record(claim_id)["conditions"]:
        rows.append((", ".join(f"{k} = {v}" for k, v in c["changed"].items()), c["measured"]))
    return rows
