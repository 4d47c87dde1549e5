// SPDX-License-Identifier: MIT
// A fixture of tests/layers/: a lab header that includes the engine, in angle brackets.
#pragma once
#include <model/scene.h>
