// When the particles are put in cell order again (host/engine/reorder_schedule.h): every N list
// rebuilds, and, unless reorder=N was named, not before the batches since the last reorder took
// 9 times its wall time, so that a reorder costing more than its steps (a GPU's download and
// upload) takes at most a tenth of the run.
#include <catch2/catch.hpp>

#include "engine/reorder_schedule.h"
#include "engine/step_program.h"

using namespace repose;

TEST_CASE("a reorder is due every N rebuilds, from the first batch on", "[reorder]") {
  ReorderSchedule s(20, false);
  CHECK(s.due(0));  // nothing ordered yet
  s.reordered(0, 5.0);
  CHECK_FALSE(s.due(19));
  CHECK(s.due(20));  // uncapped: a costly reorder is still done when named
  s.restart();
  CHECK(s.due(3));
  CHECK_FALSE(ReorderSchedule(0, true).due(100));  // reorder=0: the case's order
}

TEST_CASE("a capped reorder waits until the steps since took 9 times its cost", "[reorder]") {
  ReorderSchedule s(20, true);
  s.reordered(100, 0.2);  // a 0.2 s reorder (a million grains' state down and up)
  s.stepped(1.0);
  CHECK_FALSE(s.due(119));  // neither rebuilds nor time
  CHECK_FALSE(s.due(140));  // 40 rebuilds, but 1.0 s of steps < 9 x 0.2 s
  s.stepped(0.79);
  CHECK_FALSE(s.due(140));
  s.stepped(0.02);  // 1.81 s
  CHECK(s.due(140));
  s.reordered(140, 0.01);  // cheaper now: the next one is due by its rebuilds again
  s.stepped(0.1);
  CHECK_FALSE(s.due(159));
  CHECK(s.due(160));
}

TEST_CASE("reorder=N in a variant is exact; the default is capped", "[reorder]") {
  CHECK(KernelVariant{}.reorder_capped);
  CHECK(KernelVariant::parse("lean").reorder_capped);
  KernelVariant named = KernelVariant::parse("reorder=20");
  CHECK_FALSE(named.reorder_capped);
  CHECK(named.reorder == 20);
  CHECK(named.name() != KernelVariant{}.name());  // a bench row tells the two apart
}
