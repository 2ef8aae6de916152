"""JUnit XML of the :class:`~.document.Document`: one test case per scene for CI systems.

Classname ``ballbench.<kind>``; a failure names the failed checks, known gaps
are skipped tests, so are scenes that do not apply to their case (the reason as the message), inconclusive scenes
(no conclusive reference at the run's fidelity; the reason as the message) and scenes an interrupted run did not
reach;
each case's system-out holds the wall time against the budget and every check.
"""
from __future__ import annotations

import xml.etree.ElementTree as ET

from ballbench.validation.report.document import Document
from ballbench.validation.report.rows import fmt_time


def render(document: Document) -> bytes:
    """The XML document (UTF-8, with declaration)."""
    counted = document.tally
    verdicts = document.verdicts
    suite = ET.Element("testsuite", name="ballbench", tests=str(len(verdicts) + len(counted.not_run)),
                       failures=str(counted.counts["fail"]), errors=str(counted.counts["error"]),
                       skipped=str(counted.counts["known gap"] + counted.counts["not applicable"]
                                   + counted.counts["inconclusive"]
                                   + len(counted.not_run)),
                       time=f"{sum(v.wall_time_s for v in verdicts):.3f}")
    for v in verdicts:
        case = ET.SubElement(suite, "testcase", classname=f"ballbench.{v.kind}", name=v.name,
                             time=f"{v.wall_time_s:.3f}")
        if v.status == "error":
            ET.SubElement(case, "error", message=v.error or "no checked output").text = v.error
        elif v.status == "fail":
            message = v.failures[0].strip() if v.failures else "failed"
            ET.SubElement(case, "failure", message=message).text = "\n".join(v.failures)
        elif v.status == "not applicable":
            ET.SubElement(case, "skipped", message="does not apply: " + v.reason)
        elif v.status == "inconclusive":
            ET.SubElement(case, "skipped", message="inconclusive: " + v.inconclusive)
        elif v.status == "known gap":
            ET.SubElement(case, "skipped", message="known gap: " + "; ".join(v.gaps))
        budget = f"wall time {fmt_time(v.wall_time_s)}, budget {v.budget}"
        ET.SubElement(case, "system-out").text = "\n".join([budget, *v.checks])
    for name in counted.not_run:
        case = ET.SubElement(suite, "testcase", classname="ballbench", name=name, time="0")
        ET.SubElement(case, "skipped", message="not run: the run was interrupted")
    return ET.tostring(suite, encoding="utf-8", xml_declaration=True)
