#pragma once
/// @file solvers.hpp
/// Module umbrella: every solver of the normal problem, their settings and workspaces, the
/// solver spec and AnySolver, and batches. Including it instantiates nothing.

#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/solver_options.hpp"
#include "fastnorm/warm_start.hpp"
#include "fastnorm/norm_solver.hpp"
#include "fastnorm/fft_convolution.hpp"
#include "fastnorm/cg_solver.hpp"
#include "fastnorm/strips.hpp"
#include "fastnorm/bases.hpp"
#include "fastnorm/reduced_solver.hpp"
#include "fastnorm/solver_spec.hpp"
#include "fastnorm/solver_from_spec.hpp"
#include "fastnorm/any_solver.hpp"
#include "fastnorm/batch.hpp"
