// A campaign over 2 MPI ranks on this machine stores exactly what a local campaign stores.
#include <catch2/catch.hpp>

#include "calibrate_support.h"

using namespace repose;

TEST_CASE("2 MPI ranks give the same database contents as a local run") {
  if (!test::have_program("mpirun")) {
    WARN("mpirun not found: the MPI campaign test did not run (install openmpi-bin)");
    return;
  }
  std::string dir = test::scratch_dir("mpi");
  test::write_text(dir + "/plan.toml", test::small_ccd_plan());
  auto local = test::run_repose("calibrate " + dir + "/plan.toml --out " + dir + "/local --jobs 2 --quiet");
  INFO(local.output);
  REQUIRE(local.status == 0);
  // Rank 0 simulates with one thread and hands runs to rank 1; both simulate.
  const std::string mpirun =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none "
      "mpirun --allow-run-as-root --oversubscribe -n 2 " + std::string(REPOSE_BINARY) + " calibrate " + dir +
      "/plan.toml --out " + dir + "/mpi --jobs 1 2>&1";
  FILE* pipe = popen(mpirun.c_str(), "r");
  REQUIRE(pipe);
  std::string output;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  int status = pclose(pipe);
  INFO(output);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
  const auto local_rows = test::database_rows(dir + "/local/campaign.sqlite");
  CHECK(local_rows.size() == 13);
  CHECK(test::database_rows(dir + "/mpi/campaign.sqlite") == local_rows);
  CHECK(output.find("rank 1)") != std::string::npos);  // rank 1 did run simulations
}
