// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Deprecated path, kept for one release: the validation code is the library cubespring::validation
// now (docs/architecture.md). Include "cubespring/validation/experiments.h" and link cubespring::validation.
#pragma once

#include "cubespring/validation/experiments.h"
