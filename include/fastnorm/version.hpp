#pragma once
/// @file version.hpp
/// fastnorm's version; CMake reads FASTNORM_VERSION_* from this file.

#define FASTNORM_VERSION_MAJOR 0
#define FASTNORM_VERSION_MINOR 1
#define FASTNORM_VERSION_PATCH 0
