#pragma once
// Text inside XML or HTML (element content and quoted attribute values): the five
// characters with a meaning there as their entities.
#include <string>

namespace snapfit {

// & < > " ' as &amp; &lt; &gt; &quot; &apos;; everything else as it is.
std::string escape_markup(const std::string& text);

}  // namespace snapfit
