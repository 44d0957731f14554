#pragma once
// A fixture for checks/layering_catches_an_upward_include: a volume/ header that includes
// a header of report/, a higher layer.
#include "report/svg_chart.hpp"
