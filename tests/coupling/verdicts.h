// The verdicts of the coupling's unit tests: each check prints PASS or FAIL
// with what it checks, to stdout and to the file `output` that the test
// machinery compares; the test's exit code says whether all passed.

#ifndef yarn_impact_tests_coupling_verdicts_h
#define yarn_impact_tests_coupling_verdicts_h

#include <cstdio>
#include <fstream>
#include <string>

namespace Verdicts
{
  /** Whether every check so far passed. */
  inline bool all_passed = true;

  /** Record the check @p what, passed when @p ok. */
  inline void
  check(const bool ok, const std::string &what)
  {
    static std::ofstream verdicts("output");
    verdicts << (ok ? "PASS " : "FAIL ") << what << std::endl;
    std::printf("%s %s\n", ok ? "PASS" : "FAIL", what.c_str());
    all_passed = all_passed && ok;
  }
} // namespace Verdicts

#endif
