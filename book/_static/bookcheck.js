// Self-check for `make check-browser`: once the page has loaded and MathJax has finished
// typesetting, record on <html> how many images failed to load and that typesetting is done.
// Harmless for readers: it only sets two data attributes.
window.addEventListener("load", function () {
  var done = function (mathState) {
    var images = Array.prototype.slice.call(document.images);
    var broken = images.filter(function (img) { return !(img.complete && img.naturalWidth > 0); });
    var root = document.documentElement;
    root.setAttribute("data-check-images", images.length + " " + broken.length);
    root.setAttribute("data-check-broken", broken.map(function (img) { return img.getAttribute("src"); }).join(" "));
    root.setAttribute("data-check-math", mathState);
  };
  var mj = window.MathJax;
  if (mj && mj.startup && mj.startup.promise) {
    mj.startup.promise.then(function () { done("typeset"); }, function () { done("failed"); });
  } else {
    done(document.querySelector(".math") ? "no-renderer" : "no-math");
  }
});
