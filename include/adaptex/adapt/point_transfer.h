#pragma once
/// \file point_transfer.h
/// Forwards to paint/point_transfer.h.
#include "adaptex/paint/point_transfer.h"
