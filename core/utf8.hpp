#pragma once
// Checks that outside text is UTF-8 before it is parsed or echoed: scene and sweep files are JSON,
// which is UTF-8 (RFC 8259 sec. 8.1), and every key or value is echoed into messages and written
// into scene.json and summary.json. A byte that is not UTF-8 is named by its value and place
// instead of being echoed, which would garble the one-line message, or reported as "not valid
// JSON", which does not say why.
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace terrace {

/// The offset of the first byte of `text` that is not part of a well-formed UTF-8 sequence
/// (Unicode 15, table 3-7: no overlong forms, no surrogates, nothing beyond U+10FFFF), or npos.
inline std::size_t firstInvalidUtf8(std::string_view text) {
    const auto* s = reinterpret_cast<const unsigned char*>(text.data());
    const std::size_t n = text.size();
    std::size_t i = 0;
    while (i < n) {
        const unsigned c = s[i];
        if (c < 0x80) {
            ++i;
            continue;
        }
        int more = 0;
        unsigned lo = 0x80, hi = 0xbf; // the range of the second byte
        if (c >= 0xc2 && c <= 0xdf)
            more = 1;
        else if (c >= 0xe0 && c <= 0xef) {
            more = 2;
            if (c == 0xe0) lo = 0xa0;
            if (c == 0xed) hi = 0x9f;
        } else if (c >= 0xf0 && c <= 0xf4) {
            more = 3;
            if (c == 0xf0) lo = 0x90;
            if (c == 0xf4) hi = 0x8f;
        } else {
            return i;
        }
        for (int k = 1; k <= more; ++k) {
            if (i + k >= n) return i;
            const unsigned b = s[i + k];
            if (k == 1 ? (b < lo || b > hi) : (b < 0x80 || b > 0xbf)) return i;
        }
        i += std::size_t(more) + 1;
    }
    return std::string_view::npos;
}

/// "byte 0xff at line 3, column 17" for the byte at `offset` of `text` (columns count bytes).
inline std::string placeOfByte(std::string_view text, std::size_t offset) {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < offset && i < text.size(); ++i)
        if (text[i] == '\n')
            ++line, column = 1;
        else
            ++column;
    char out[80];
    std::snprintf(out, sizeof out, "byte 0x%02x at line %zu, column %zu",
                  unsigned(static_cast<unsigned char>(text[offset])), line, column);
    return out;
}

/// Why a one-line argument (a --set) is refused: "not UTF-8 text (byte 0xff at character 5); …".
inline std::string utf8Problem(std::string_view text, std::size_t offset) {
    char out[120];
    std::snprintf(out, sizeof out,
                  "not UTF-8 text (byte 0x%02x at character %zu): keys and values are UTF-8",
                  unsigned(static_cast<unsigned char>(text[offset])), offset + 1);
    return out;
}

/// `text` with every byte outside printable ASCII written as \xHH: fit to name bad input in a
/// one-line message.
inline std::string printableBytes(std::string_view text) {
    std::string out;
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 0x20 && c < 0x7f) {
            out += ch;
        } else {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(c));
            out += hex;
        }
    }
    return out;
}

} // namespace terrace
