#pragma once
// EXPECT_CONTAINS(text, part): the text (an error message, a document) holds
// part; on failure it prints the whole text.
#include <gtest/gtest.h>

#include <string>

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)
