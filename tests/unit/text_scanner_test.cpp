#include "lib/meshio/text_scanner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace lodbake {
namespace {

// Scans a string literal (which outlives the scanner).
TextScanner scan(const char* s) {
  return TextScanner(reinterpret_cast<const uint8_t*>(s), std::strlen(s));
}

TEST(TextScanner, FloatsAcceptPlusSignAndRoundTripExactly) {
  float f = 0;
  EXPECT_EQ(parse_float("+1.5", &f), NumberStatus::kOk);
  EXPECT_EQ(f, 1.5f);
  EXPECT_EQ(parse_float("-.25e1", &f), NumberStatus::kOk);
  EXPECT_EQ(f, -2.5f);
  EXPECT_EQ(parse_float("0.1", &f), NumberStatus::kOk);
  EXPECT_EQ(f, 0.1f);
  EXPECT_EQ(parse_float("16777217", &f), NumberStatus::kOk);
  EXPECT_EQ(f, 16777216.0f) << "rounded to nearest even, as a float";
}

TEST(TextScanner, FloatSpellingsOfNanAndInfinityParse) {
  for (const char* s : {"nan", "NaN", "-nan", "+nan", "nan(123)"}) {
    float f = 0;
    EXPECT_EQ(parse_float(s, &f), NumberStatus::kOk) << s;
    EXPECT_TRUE(std::isnan(f)) << s;
  }
  for (const char* s : {"inf", "+inf", "-Inf", "INFINITY"}) {
    float f = 0;
    EXPECT_EQ(parse_float(s, &f), NumberStatus::kOk) << s;
    EXPECT_TRUE(std::isinf(f)) << s;
  }
}

TEST(TextScanner, FloatUnderflowIsZeroOverflowIsOutOfRange) {
  float f = 1;
  EXPECT_EQ(parse_float("1e-50", &f), NumberStatus::kOk);
  EXPECT_EQ(f, 0.0f);
  EXPECT_EQ(parse_float("-1e-400", &f), NumberStatus::kOk);
  EXPECT_EQ(f, 0.0f);
  EXPECT_TRUE(std::signbit(f));
  EXPECT_EQ(parse_float("1e-40", &f), NumberStatus::kOk);
  EXPECT_GT(f, 0.0f) << "subnormal kept";
  EXPECT_EQ(parse_float("1e39", &f), NumberStatus::kOutOfRange);
  EXPECT_EQ(parse_float("-1e999", &f), NumberStatus::kOutOfRange);
}

TEST(TextScanner, MalformedNumbers) {
  float f = 0;
  for (const char* s : {"", "+", "++1", "+-1", "1.5x", "zero", "0x10", "1e", "1,5", "."})
    EXPECT_EQ(parse_float(s, &f), NumberStatus::kMalformed) << "'" << s << "'";
  int64_t i = 0;
  for (const char* s : {"", "1.0", "1e3", "--1", "+-1", "12a"})
    EXPECT_EQ(parse_int64(s, &i), NumberStatus::kMalformed) << "'" << s << "'";
  uint64_t u = 0;
  EXPECT_EQ(parse_uint64("-3", &u), NumberStatus::kMalformed);
}

TEST(TextScanner, IntegersDetectOverflow) {
  int64_t i = 0;
  EXPECT_EQ(parse_int64("-9223372036854775808", &i), NumberStatus::kOk);
  EXPECT_EQ(i, std::numeric_limits<int64_t>::min());
  EXPECT_EQ(parse_int64("+42", &i), NumberStatus::kOk);
  EXPECT_EQ(i, 42);
  EXPECT_EQ(parse_int64("9223372036854775808", &i), NumberStatus::kOutOfRange);
  EXPECT_EQ(parse_int64("99999999999999999999x", &i), NumberStatus::kMalformed);
  uint64_t u = 0;
  EXPECT_EQ(parse_uint64("18446744073709551615", &u), NumberStatus::kOk);
  EXPECT_EQ(u, std::numeric_limits<uint64_t>::max());
  EXPECT_EQ(parse_uint64("18446744073709551616", &u), NumberStatus::kOutOfRange);
}

TEST(TextScanner, TokensStayOnTheirLineAndLinesCountAllEndings) {
  TextScanner s = scan("v 1 2\r\nf\t3\r\rg x\n\\\n");
  EXPECT_EQ(s.token(), "v");
  EXPECT_EQ(s.token(), "1");
  EXPECT_EQ(s.token(), "2");
  EXPECT_EQ(s.token(), "");
  EXPECT_TRUE(s.at_line_end());
  EXPECT_EQ(s.line(), 1u);
  s.skip_line();
  EXPECT_EQ(s.line(), 2u);
  EXPECT_EQ(s.token(), "f");
  EXPECT_EQ(s.token(), "3");
  s.skip_whitespace();
  EXPECT_EQ(s.line(), 4u) << "\\r\\r is two line ends";
  EXPECT_EQ(s.token(), "g");
  s.skip_line();
  EXPECT_EQ(s.token(), "\\") << "no continuation unless enabled";
  s.skip_whitespace();
  EXPECT_TRUE(s.at_end());
  EXPECT_EQ(s.line(), 6u);
  s.skip_line();  // harmless at the end
  EXPECT_TRUE(s.at_end());
}

TEST(TextScanner, LineContinuationJoinsLines) {
  TextScanner s = scan("f 1 \\\r\n 2\\\n3\n");
  s.set_line_continuation(true);
  EXPECT_EQ(s.token(), "f");
  EXPECT_EQ(s.token(), "1");
  EXPECT_EQ(s.token(), "2");
  EXPECT_EQ(s.token(), "3");
  EXPECT_EQ(s.token(), "");
  EXPECT_EQ(s.line(), 3u);
}

TEST(TextScanner, CommentsAndTokenUntil) {
  TextScanner s = scan("# a\n  # b\n\n12#c\n7");
  s.skip_whitespace_and_comments('#');
  EXPECT_EQ(s.line(), 4u);
  EXPECT_EQ(s.token_until('#'), "12");
  s.skip_whitespace_and_comments('#');
  uint64_t u = 0;
  EXPECT_EQ(s.read_uint64(&u), NumberStatus::kOk);
  EXPECT_EQ(u, 7u);
  EXPECT_EQ(s.read_uint64(&u), NumberStatus::kMissing);
  EXPECT_TRUE(s.at_end());
}

TEST(TextScanner, ReadsNeverPassTheEnd) {
  // The scanner sees only the first 3 bytes; the rest must stay unread.
  const char text[] = "1.5e+10 9";
  TextScanner s(reinterpret_cast<const uint8_t*>(text), 3);
  float f = 0;
  EXPECT_EQ(s.read_float(&f), NumberStatus::kOk);
  EXPECT_EQ(f, 1.5f);
  EXPECT_EQ(s.read_float(&f), NumberStatus::kMissing);
  TextScanner empty(nullptr, 0);
  EXPECT_TRUE(empty.at_end());
  EXPECT_EQ(empty.token(), "");
  empty.skip_whitespace_and_comments('#');
  empty.skip_line();
  EXPECT_EQ(empty.peek(), '\0');
}

TEST(TextScanner, ErrorMessagesNameLineAndToken) {
  TextScanner s = scan("\n\nv 1 zero\n");
  s.skip_whitespace();
  s.token();
  float f = 0;
  EXPECT_EQ(s.read_float(&f), NumberStatus::kOk);
  NumberStatus status = s.read_float(&f);
  EXPECT_EQ(s.number_error(status, "a coordinate"), "line 3: expected a coordinate, found 'zero'");
  status = s.read_float(&f);
  EXPECT_EQ(s.number_error(status, "a coordinate"),
            "line 3: expected a coordinate, found the end of the line");
  EXPECT_EQ(quote_token(std::string_view("a\x01\xff", 3)), "'a\\x01\\xff'");
  EXPECT_EQ(quote_token(std::string(40, 'x')), "'" + std::string(32, 'x') + "...'");
}

// The bad-input spellings read through the scanner's tokens (the table
// driven scan) give the same values, statuses and messages as parsing the
// whole token: a token ends only at a blank, a line end, the stop byte or a
// continuation, so trailing garbage stays in the token and makes it
// malformed.
TEST(TextScanner, BadSpellingsThroughTokensKeepTheirStatusAndMessage) {
  TextScanner s = scan("NaN -inf +Infinity 0x10 +1.5 1.5x 1e39 1e-50 \\q 7#c\n");
  float f = 0;
  ASSERT_EQ(s.read_float(&f), NumberStatus::kOk);
  EXPECT_TRUE(std::isnan(f));
  ASSERT_EQ(s.read_float(&f), NumberStatus::kOk);
  EXPECT_EQ(f, -std::numeric_limits<float>::infinity());
  ASSERT_EQ(s.read_float(&f), NumberStatus::kOk);
  EXPECT_EQ(f, std::numeric_limits<float>::infinity());
  EXPECT_EQ(s.read_float(&f), NumberStatus::kMalformed);
  EXPECT_EQ(s.last_token(), "0x10");
  EXPECT_EQ(s.number_error(NumberStatus::kMalformed, "a coordinate"),
            "line 1: expected a coordinate, found '0x10'");
  ASSERT_EQ(s.read_float(&f), NumberStatus::kOk);
  EXPECT_EQ(f, 1.5f);
  EXPECT_EQ(s.read_float(&f), NumberStatus::kMalformed);
  EXPECT_EQ(s.last_token(), "1.5x");
  EXPECT_EQ(s.read_float(&f), NumberStatus::kOutOfRange);
  EXPECT_EQ(s.number_error(NumberStatus::kOutOfRange, "a coordinate"),
            "line 1: a coordinate '1e39' is out of range");
  ASSERT_EQ(s.read_float(&f), NumberStatus::kOk);
  EXPECT_EQ(f, 0.0f);
  // A backslash not before a line end is part of the token.
  EXPECT_EQ(s.token(), "\\q");
  EXPECT_EQ(s.token_until('#'), "7");
  EXPECT_EQ(s.token(), "#c");
  EXPECT_TRUE(s.token().empty());
}

TEST(TextScanner, IntegerTokensKeepTheirStatus) {
  TextScanner s = scan("+3 -0 0x1f 12a 99999999999999999999 -9223372036854775808\t4\r\n");
  int64_t i = 0;
  ASSERT_EQ(s.read_int64(&i), NumberStatus::kOk);
  EXPECT_EQ(i, 3);
  ASSERT_EQ(s.read_int64(&i), NumberStatus::kOk);
  EXPECT_EQ(i, 0);
  EXPECT_EQ(s.read_int64(&i), NumberStatus::kMalformed);
  EXPECT_EQ(s.last_token(), "0x1f");
  EXPECT_EQ(s.read_int64(&i), NumberStatus::kMalformed);
  EXPECT_EQ(s.read_int64(&i), NumberStatus::kOutOfRange);
  EXPECT_EQ(s.number_error(NumberStatus::kOutOfRange, "an index"),
            "line 1: an index '99999999999999999999' is out of range");
  ASSERT_EQ(s.read_int64(&i), NumberStatus::kOk);
  EXPECT_EQ(i, std::numeric_limits<int64_t>::min());
  ASSERT_EQ(s.read_int64(&i), NumberStatus::kOk);
  EXPECT_EQ(i, 4);
  EXPECT_EQ(s.read_int64(&i), NumberStatus::kMissing);
  s.skip_whitespace();
  EXPECT_EQ(s.line(), 2u);
  EXPECT_TRUE(s.at_end());
}

// A continuation inside the token scan ends the token, and the scan goes on
// after it on the next line.
TEST(TextScanner, ContinuationEndsATokenInTheTableScan) {
  TextScanner s = scan("f 1\\\n2 3\\\r\n4\n");
  s.set_line_continuation(true);
  EXPECT_EQ(s.token(), "f");
  EXPECT_EQ(s.token(), "1");
  EXPECT_EQ(s.token(), "2");
  EXPECT_EQ(s.token(), "3");
  EXPECT_EQ(s.token(), "4");
  EXPECT_EQ(s.line(), 3u);
  EXPECT_TRUE(s.token().empty());
}

TEST(PrepareText, DecodesUtf16WithByteOrderMark) {
  const uint8_t be[] = {0xfe, 0xff, 0, 'v', 0, ' ', 0, '1', 0x00, 0xe9, 0, '\n'};
  const uint8_t* data = be;
  size_t size = sizeof(be);
  std::vector<uint8_t> storage;
  std::string note;
  ASSERT_TRUE(prepare_text(&data, &size, &storage, &note).is_ok());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(data), size), "v 1?\n");
  EXPECT_EQ(note, "decoded UTF-16BE text");
  const uint8_t le[] = {0xff, 0xfe, 'f', 0, ' ', 0};
  data = le;
  size = sizeof(le);
  ASSERT_TRUE(prepare_text(&data, &size, &storage, &note).is_ok());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(data), size), "f ");
  const uint8_t odd[] = {0xff, 0xfe, 'f'};
  data = odd;
  size = sizeof(odd);
  EXPECT_FALSE(prepare_text(&data, &size, &storage, &note).is_ok());
}

TEST(PrepareText, SkipsUtf8BomAndRejectsNulBytes) {
  const uint8_t bom[] = {0xef, 0xbb, 0xbf, 'O', 'F', 'F'};
  const uint8_t* data = bom;
  size_t size = sizeof(bom);
  std::vector<uint8_t> storage;
  std::string note;
  ASSERT_TRUE(prepare_text(&data, &size, &storage, &note).is_ok());
  EXPECT_EQ(size, 3u);
  EXPECT_EQ(data[0], 'O');
  EXPECT_TRUE(note.empty());
  const uint8_t binary[] = {'v', ' ', 0, '1'};
  data = binary;
  size = sizeof(binary);
  Status status = prepare_text(&data, &size, &storage, &note);
  ASSERT_FALSE(status.is_ok());
  EXPECT_EQ(status.message(), "binary data where text was expected: NUL byte at byte 2");
}

}  // namespace
}  // namespace lodbake
