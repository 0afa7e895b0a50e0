#pragma once
/// @file fastnorm.hpp
/// Umbrella header: everything public in fastnorm.

#include "fastnorm/version.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/influence.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/active_set.hpp"
#include "fastnorm/norm_solver.hpp"
#include "fastnorm/fft_convolution.hpp"
#include "fastnorm/cg_solver.hpp"
#include "fastnorm/strips.hpp"
#include "fastnorm/bases.hpp"
#include "fastnorm/reduced_solver.hpp"
#include "fastnorm/any_solver.hpp"
#include "fastnorm/batch.hpp"
#include "fastnorm/hertz.hpp"
#include "fastnorm/case_file.hpp"
#include "fastnorm/wheelrail.hpp"
