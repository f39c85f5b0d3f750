#pragma once
// gate-report.xml: JUnit XML as Jenkins (junit plugin) and GitLab (artifacts:reports:junit)
// read it. Layout: <testsuites> holding one <testsuite> per case, holding one <testcase> per
// bound, named by the metric, classname "giq.gate.<case>". A case that could not be rendered
// or scored (Outcome::error) carries <error message type="ERROR"> on each bound; FAIL and a
// failing UNRESOLVED carry <failure message type>; SKIP and a non-failing UNRESOLVED carry
// <skipped message> (neither is a pass); WARN passes with the warning in <system-out>. Counts
// follow the common JUnit schema (tests, failures, errors, skipped on both levels); each
// testcase's time is its case's wall time shared equally among the case's bounds.

#include <string>
#include <vector>

#include "giq/gate/evaluation.h"

namespace giq::gate {

// `seconds_per_case`: wall time per case name (rendering and scoring), 0 where unknown.
std::string junit_xml(const std::vector<Outcome>& outcomes,
                      const std::vector<std::pair<std::string, double>>& seconds_per_case);

}  // namespace giq::gate
