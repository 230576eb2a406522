// The data a page carries: one JSON object in <script id="snapfit-data" type="application/json">,
// written by the C++ side (report/html_page.h). Large numeric arrays come as base64 of
// little-endian float32 or bytes (report/page_encoding.h).

export function readPageData() {
  const node = document.getElementById('snapfit-data');
  if (!node) throw new Error('this page has no snapfit-data block');
  return JSON.parse(node.textContent);
}

function bytesOf(base64) {
  const text = atob(base64 || '');
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
  return bytes;
}

export function float32s(base64) {
  const bytes = bytesOf(base64);
  return new Float32Array(bytes.buffer, 0, bytes.length >> 2);
}

export function uint8s(base64) {
  return bytesOf(base64);
}

// A number for people: up to `digits` significant digits, no exponent for ordinary sizes,
// no trailing zeros (5e-5, not 5.00000e-5).
export function formatNumber(value, digits = 4) {
  if (value === null || value === undefined || !Number.isFinite(value)) return String(value);
  if (value === 0) return '0';
  const a = Math.abs(value);
  if (a >= 1e6 || a < 1e-4) return value.toExponential(digits - 1).replace(/\.?0+e/, 'e');
  return String(Number(value.toPrecision(digits)));
}

export function element(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) {
    if (key === 'class') node.className = value;
    else if (key === 'text') node.textContent = value;
    else node.setAttribute(key, value);
  }
  for (const child of children) node.append(child);
  return node;
}
