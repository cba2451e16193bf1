#pragma once
/// \file point_transfer.h
/// transfer_points() lives in the paint layer (paint/point_transfer.h), where the asset measure uses
/// it too; this header keeps the adapt-layer include working.
#include "adaptex/paint/point_transfer.h"
