// The one translation unit that holds Catch2's main(); every test folder links it.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include "experiments/registry.h"

// As repose's main() does: the case loader reads [experiment] tables through the experiments.
static const bool experiments_installed = (repose::install_experiments(), true);
