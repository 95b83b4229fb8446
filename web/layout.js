export function element(tag, style, parent) {
  const e = document.createElement(tag);
  Object.assign(e.style, style);
  parent.appendChild(e);
  return e;
}

// The page a session draws on, over the whole window in the study's surround: the header, question
// and hint lines around the images, a message line, and `imageCount` hidden <img> elements.
export function buildPage(root, study, imageCount) {
  const grey = `rgb(${study.surround},${study.surround},${study.surround})`;
  const ink = study.surround >= 128 ? "#141414" : "#ebebeb";
  const page = element("div", { position: "fixed", inset: "0", background: grey, color: ink, overflow: "hidden",
                                fontFamily: "sans-serif", fontSize: `${study.font_px}px`, textAlign: "center" }, root);
  const text = (top) => element("div", { position: "absolute", left: "10%", width: "80%", top, whiteSpace: "pre-wrap" }, page);
  const [header, question, hint, message] = ["0px", "0px", "0px", "40%"].map(text);
  const images = Array.from({ length: imageCount }, () => element("img", { position: "absolute", imageRendering: "pixelated", display: "none" }, page));
  return { page, ink, header, question, hint, message, images };
}

// Where a trial's images go on the page, in device pixels, so that each is shown at 1:1 device
// pixels as the app shows it: a row of n images of one size with the study's gap, centred under
// the texts, every image starting on a device pixel.

// The smallest step in device pixels that is a whole number of CSS pixels at this ratio: an image
// placed on it starts exactly on a device pixel (Chromium rounds an image's position to whole CSS
// pixels at some ratios, measured at 1.25 and 2).
function deviceSnap(dpr) {
  for (let n = 1; n <= 64; ++n) {
    const css = n / dpr;
    if (Math.abs(css - Math.round(css)) < 1e-9) return n;
  }
  return 1;
}

// The row's places ({xs: each image's left edge, y, width, height, dpr}), or null when the window
// is too small to show it at 1:1 with the texts above and below.
export function rowLayout(study, condition, count, innerWidth, innerHeight, dpr) {
  const W = Math.round(innerWidth * dpr), H = Math.round(innerHeight * dpr);
  const { width: w, height: h } = condition;
  const line = study.font_px * 1.35 * dpr;
  const side = Math.ceil(study.font_px * dpr), top = Math.ceil(line * 4.5), bottom = Math.ceil(line * 2.5);
  const row = count * w + (count - 1) * study.gap_px;
  if (row + 2 * side > W || h + top + bottom > H) return null;
  const snap = deviceSnap(dpr);
  const down = (x) => Math.floor(x / snap) * snap;
  const xs = [down((W - row) / 2)];
  while (xs.length < count) xs.push(Math.ceil((xs[xs.length - 1] + w + study.gap_px) / snap) * snap);
  if (xs[count - 1] + w + side > W) return null;
  const y = down(top + Math.max(0, (H - top - bottom - h) / 2));
  return { xs, y, width: w, height: h, dpr };
}

// Places the page's <img> elements on a layout's places (hidden where files has no entry); with
// `deep` (a 16-bit study's DeepImages) the images are drawn there instead, each frame.
export function placeImages(images, place, files, decoded, deep = null) {
  if (deep) {
    deep.items = place ? files.map((file, i) => ({ file, x: place.xs[i], y: place.y, width: place.width, height: place.height })) : [];
    files = [];
  }
  images.forEach((img, i) => {
    if (!place || i >= files.length) return void (img.style.display = "none");
    const src = decoded.get(files[i]).src;
    if (img.getAttribute("src") !== src) img.setAttribute("src", src);
    Object.assign(img.style, { display: "block", left: `${place.xs[i] / place.dpr}px`, top: `${place.y / place.dpr}px`,
                               width: `${place.width / place.dpr}px`, height: `${place.height / place.dpr}px` });
  });
}

// Decodes one of a condition's images for placeImages: an <img> source, or with `deep` its 16-bit
// codes as a texture (then nothing is returned).
export async function decodeImage(file, condition, deep = null) {
  if (deep) return void (await deep.load(file, condition.width, condition.height));
  const img = new Image();
  img.src = file;
  await img.decode();
  return img;
}
