#pragma once
#include "graph/motion_graph.hpp"
