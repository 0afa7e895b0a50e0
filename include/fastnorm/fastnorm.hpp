#pragma once
/// @file fastnorm.hpp
/// Umbrella header: everything public in fastnorm, by module (docs/architecture.md §1).
/// Including it costs about the parse of Eigen's headers and instantiates nothing
/// (docs/contributing.md, compile cost).

#include "fastnorm/version.hpp"
#include "fastnorm/constants.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/hertz.hpp"
#include "fastnorm/solvers.hpp"
#include "fastnorm/tangential_influence.hpp"
#include "fastnorm/fastsim.hpp"
#include "fastnorm/strip_theory.hpp"
#include "fastnorm/kalker_coefficients.hpp"
#include "fastnorm/tangential_solver.hpp"
#include "fastnorm/io.hpp"
#include "fastnorm/contact_table_file.hpp"
#include "fastnorm/wheelrail.hpp"
